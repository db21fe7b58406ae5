// The scene file's "networks" (docs/scene-format.md#networks): Konev18 pipe networks and
// shafts from GIS layers or inline polylines, with attributes mapped to radius, wall
// thickness, water level and depth below the terrain.
#include "scene/network_json.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <regex>
#include <sstream>

#include "cutaway/geometry/ground_height.hpp"
#include "cutaway/io/gis_import.hpp"

namespace cutaway::json_reader {

namespace {

// A per-feature value: a constant, or {"field": NAME, "scale": k, "default": v}.
struct Attribute {
  double constant = 0.0;
  std::string field;  // empty: the constant
  double scale = 1.0;
  std::optional<double> fallback;
  double lo = 0.0, hi = 0.0;  // the range a field's scaled value must lie in, as a constant's
};

Attribute attribute(const Context& ctx, const json& j, const std::string& ptr, double lo,
                    double hi) {
  Attribute a;
  a.lo = lo, a.hi = hi;
  if (j.is_number()) {
    a.constant = number(ctx, j, ptr, lo, hi);
    return a;
  }
  ObjectReader r(ctx, j, ptr);
  a.field = string(ctx, r.require("field"), r.at("field"));
  if (const json* v = r.take("scale")) a.scale = number(ctx, *v, r.at("scale"), -1e9, 1e9);
  if (const json* v = r.take("default")) a.fallback = number(ctx, *v, r.at("default"), lo, hi);
  r.finish();
  return a;
}

// The attribute's value for a feature whose fields were read in `fields` order; throws with
// the feature named when a value is missing and there is no default, or lies outside the
// attribute's range.
double value(const Context& ctx, const Attribute& a, const std::vector<std::string>& fields,
             const std::vector<double>& values, const std::string& where, std::int64_t fid) {
  if (a.field.empty()) return a.constant;
  const auto at = std::size_t(std::find(fields.begin(), fields.end(), a.field) - fields.begin());
  const double v = values[at];
  if (!std::isnan(v)) {
    const double scaled = v * a.scale;
    // GIS layers write 0 (or −1) for an unknown diameter: a size takes the default there.
    if (scaled <= 0.0 && a.lo > 0.0 && a.fallback) return *a.fallback;
    if (!(scaled >= a.lo && scaled <= a.hi)) {
      std::ostringstream s;
      s << "feature " << fid << " has \"" << a.field << "\" = " << v;
      if (a.scale != 1.0) s << " (× scale: " << scaled << ")";
      s << ", outside [" << a.lo << ", " << a.hi << "]";
      ctx.fail(where, s.str());
    }
    return scaled;
  }
  if (a.fallback) return *a.fallback;
  ctx.fail(where, "feature " + std::to_string(fid) + " has no value for \"" + a.field +
                      "\" (give \"default\")");
}

struct PipeAttributes {
  Attribute radius{0.5}, wallThickness{0.08}, waterLevel{0.0}, depth{2.0};
  std::vector<std::string> fields() const {
    std::vector<std::string> f;
    for (const Attribute* a : {&radius, &wallThickness, &waterLevel, &depth})
      if (!a->field.empty() && std::find(f.begin(), f.end(), a->field) == f.end())
        f.push_back(a->field);
    return f;
  }
};

// Reads the attribute keys shared by pipe entries and the network's defaults.
void attributeKeys(const Context& ctx, ObjectReader& r, PipeAttributes& a) {
  if (const json* v = r.take("radius")) a.radius = attribute(ctx, *v, r.at("radius"), 1e-4, 1e3);
  if (const json* v = r.take("wallThickness"))
    a.wallThickness = attribute(ctx, *v, r.at("wallThickness"), 1e-5, 1e3);
  if (const json* v = r.take("waterLevel"))
    a.waterLevel = attribute(ctx, *v, r.at("waterLevel"), 0, 1e3);
  if (const json* v = r.take("depth")) a.depth = attribute(ctx, *v, r.at("depth"), -1e4, 1e4);
}

// Radius, wall and water made consistent: 0 < wall ≤ r, water within the bore.
// `feature`: the GIS feature the values came from, −1 for inline lines.
Pipe makePipe(const Context& ctx, const std::string& where, std::int64_t feature, double radius,
              double wall, double water) {
  std::ostringstream problem;
  if (!(radius > 0))
    problem << "pipe radius " << radius << " must be positive";
  else if (!(wall < radius))
    problem << "wall thickness " << wall << " must be less than the radius " << radius;
  if (!problem.str().empty())
    ctx.fail(where,
             (feature >= 0 ? "feature " + std::to_string(feature) + ": " : "") + problem.str());
  Pipe p;
  p.radius = float(radius);
  p.wallThickness = float(std::clamp(wall, 1e-6 * radius, radius));
  p.waterLevel = float(std::clamp(water, 0.0, 2.0 * double(p.innerRadius())));
  return p;
}

// The lowest height of `pipe`'s axis over the disc of `radius` around `at` (horizontal x, z),
// or +∞ where it does not pass: along a segment the height is linear, so it is lowest at one
// end of the stretch within the disc.
float lowestWithin(const Pipe& pipe, glm::vec2 at, float radius) {
  float lowest = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i + 1 < pipe.nodes.size(); ++i) {
    const glm::vec3 a = pipe.nodes[i], b = pipe.nodes[i + 1];
    const glm::dvec2 d(b.x - a.x, b.z - a.z), f(a.x - at.x, a.z - at.y);
    // |f + t·d|² = r²: the stretch [t0, t1] of the segment inside the disc.
    const double dd = glm::dot(d, d), fd = glm::dot(f, d);
    const double c = glm::dot(f, f) - double(radius) * double(radius);
    double t0 = 0.0, t1 = 1.0;
    if (dd == 0.0) {  // vertical: within the disc whole, or not at all
      if (c > 0.0) continue;
    } else {
      const double disc = fd * fd - dd * c;
      if (disc < 0.0) continue;
      t0 = std::max(0.0, (-fd - std::sqrt(disc)) / dd);
      t1 = std::min(1.0, (-fd + std::sqrt(disc)) / dd);
      if (t0 > t1) continue;
    }
    for (const double t : {t0, t1}) lowest = std::min(lowest, float(a.y + t * (b.y - a.y)));
  }
  return lowest;
}

}  // namespace

void readNetworks(const Context& ctx, const json& j, const std::string& ptr, Scene& scene) {
  if (!j.is_array()) ctx.fail(ptr, "expected an array of networks, got " + typeName(j));
  // The ground under networks on the same terrain objects, built once (a large grid's takes
  // seconds).
  std::map<std::vector<std::size_t>, GroundHeight> grounds;  // by the objects' indices
  for (std::size_t n = 0; n < j.size(); ++n) {
    const std::string np = ptr + "/" + std::to_string(n);
    ObjectReader r(ctx, j[n], np);
    PipeNetwork net;
    net.name = name(ctx, r.require("name"), r.at("name"), "network");
    for (const PipeNetwork& other : scene.networks)
      if (other.name == net.name)
        ctx.fail(r.at("name"), "two networks are named " + quote(net.name));

    // Heights come from the terrain objects: nodes without z, and the shafts' rims.
    std::vector<std::size_t> terrain;
    std::string terrainPattern;
    if (const json* v = r.take("terrain")) {
      const std::regex pattern = regex(ctx, *v, r.at("terrain"));
      terrainPattern = string(ctx, *v, r.at("terrain"));
      for (std::size_t i = 0; i < scene.objects.size(); ++i)
        if (!scene.objects[i].proxy && scene.objects[i].named(pattern)) terrain.push_back(i);
      if (terrain.empty())
        ctx.fail(r.at("terrain"), "no object name matches " + quote(terrainPattern));
    }
    auto found = grounds.find(terrain);
    if (found == grounds.end()) {
      std::vector<const Mesh*> meshes;
      std::vector<glm::mat4> transforms;
      for (std::size_t i : terrain)
        meshes.push_back(scene.objects[i].mesh.get()),
            transforms.push_back(scene.objects[i].transform);
      found = grounds.emplace(terrain, GroundHeight(meshes, transforms)).first;
    }
    const GroundHeight& ground = found->second;
    const auto groundAt = [&](glm::vec2 xz) -> float { return ground.at(xz).value_or(0.0f); };

    PipeAttributes defaults;
    attributeKeys(ctx, r, defaults);
    std::optional<glm::vec2> cutFractions;
    if (const json* v = r.take("cut")) {
      ObjectReader cr(ctx, *v, r.at("cut"));
      const float from = float(number(ctx, cr.require("from"), cr.at("from"), 0, 1));
      const float to = float(number(ctx, cr.require("to"), cr.at("to"), 0, 1));
      cr.finish();
      if (!(to > from)) ctx.fail(r.at("cut"), "\"to\" must be greater than \"from\"");
      cutFractions = glm::vec2(from, to);
    }
    if (const json* v = r.take("mode"))
      net.mode = oneOf(ctx, *v, r.at("mode"), {"billboards", "mesh"}) == "mesh"
                     ? PipeNetwork::Mode::Mesh
                     : PipeNetwork::Mode::Billboards;
    if (const json* v = r.take("color")) net.color = color(ctx, *v, r.at("color"));
    if (const json* v = r.take("insideColor"))
      net.insideColor = color(ctx, *v, r.at("insideColor"));
    if (const json* v = r.take("cutColor")) net.cutColor = color(ctx, *v, r.at("cutColor"));
    if (const json* v = r.take("waterColors")) {
      if (!v->is_array() || v->size() != 2) ctx.fail(r.at("waterColors"), "expected [low, high]");
      net.waterLow = color(ctx, (*v)[0], r.at("waterColors") + "/0");
      net.waterHigh = color(ctx, (*v)[1], r.at("waterColors") + "/1");
    }
    if (const json* v = r.take("shaftOpening"))
      net.shaftOpening = float(number(ctx, *v, r.at("shaftOpening"), -1, 1));
    if (const json* v = r.take("radiusScale"))
      net.radiusScale = float(number(ctx, *v, r.at("radiusScale"), 1e-3, 1e3));
    float maxBend = 60.0f;
    if (const json* v = r.take("maxBend"))
      maxBend = float(number(ctx, *v, r.at("maxBend"), 1, 180));

    const json& pipes = r.require("pipes");
    if (!pipes.is_array() || pipes.empty())
      ctx.fail(r.at("pipes"), "expected a non-empty array of pipe layers or inline lines");
    for (std::size_t e = 0; e < pipes.size(); ++e) {
      const std::string ep = r.at("pipes") + "/" + std::to_string(e);
      ObjectReader er(ctx, pipes[e], ep);
      PipeAttributes a = defaults;
      attributeKeys(ctx, er, a);
      const json* file = er.take("file");
      const json* lines = er.take("lines");
      if (!!file == !!lines)
        ctx.fail(ep, "a pipe entry needs exactly one of \"file\" or \"lines\"");
      std::string layer;
      if (const json* v = er.take("layer")) layer = string(ctx, *v, er.at("layer"));
      er.finish();
      const auto place = [&](glm::vec3 p, bool hasZ, double depth) {
        // Nodes without a height lie `depth` under the terrain (the pipe's axis).
        if (!hasZ) p.y = groundAt({p.x, p.z}) - float(depth);
        return p;
      };
      if (file) {
        GisImportOptions gis = gisImportOptions(ctx.geo);
        gis.layer = layer;
        gis.attributes = a.fields();
        GisLines imported;
        try {
          imported = importGisLines(ctx.baseDir / string(ctx, *file, er.at("file")), gis);
        } catch (const Error& err) {
          ctx.fail(er.at("file"), err.what());
        }
        for (const GisPolyline& line : imported.polylines) {
          const auto get = [&](const Attribute& at) {
            return value(ctx, at, gis.attributes, line.attributes, er.at("file"), line.featureId);
          };
          Pipe p = makePipe(ctx, er.at("file"), line.featureId, get(a.radius), get(a.wallThickness),
                            get(a.waterLevel));
          p.featureId = line.featureId;
          const double depth = get(a.depth);
          for (const glm::vec3& q : line.points)
            p.nodes.push_back(place(GeoFrame::toScene(q), imported.hasZ, depth));
          net.pipes.push_back(std::move(p));
        }
      } else {
        if (!lines->is_array() || lines->empty()) ctx.fail(er.at("lines"), "expected polylines");
        if (!a.fields().empty())
          ctx.fail(ep, "inline lines have no attribute fields: give constants");
        for (std::size_t i = 0; i < lines->size(); ++i) {
          const std::string lp = er.at("lines") + "/" + std::to_string(i);
          const json& line = (*lines)[i];
          if (!line.is_array()) ctx.fail(lp, "expected an array of [x, y, z] or [x, z] nodes");
          Pipe p = makePipe(ctx, lp, -1, a.radius.constant, a.wallThickness.constant,
                            a.waterLevel.constant);
          for (std::size_t k = 0; k < line.size(); ++k) {
            const std::string q = lp + "/" + std::to_string(k);
            if (!line[k].is_array() || (line[k].size() != 3 && line[k].size() != 2))
              ctx.fail(q, "expected [x, y, z] or [x, z] (y from the terrain minus \"depth\")");
            const bool hasZ = line[k].size() == 3;
            glm::vec3 node(
                float(number(ctx, line[k][0], q + "/0", -1e9, 1e9)), 0.0f,
                float(number(ctx, line[k][hasZ ? 2 : 1], q + (hasZ ? "/2" : "/1"), -1e9, 1e9)));
            if (hasZ) node.y = float(number(ctx, line[k][1], q + "/1", -1e9, 1e9));
            node = place(node, hasZ, a.depth.constant);
            // Zero-length segments carry no direction (eqs. 4–6): repeated nodes are dropped.
            if (p.nodes.empty() || glm::length(node - p.nodes.back()) > 1e-6f)
              p.nodes.push_back(node);
          }
          if (p.nodes.size() < 2) ctx.fail(lp, "a pipe needs at least two distinct nodes");
          net.pipes.push_back(std::move(p));
        }
      }
    }
    if (net.pipes.empty()) ctx.fail(r.at("pipes"), "the layers hold no pipes");
    if (cutFractions)
      for (Pipe& p : net.pipes) p.cut = *cutFractions * p.length();

    std::vector<Joint> joints = splitSharpBends(net, maxBend);
    resolveCutIntersections(net, 0.0f);

    if (const json* v = r.take("shafts")) {
      ObjectReader sr(ctx, *v, r.at("shafts"));
      ShaftDefaults sd;
      Attribute radius{sd.radius}, wall{sd.wallThickness}, water{sd.waterLevel};
      if (const json* x = sr.take("radius"))
        radius = attribute(ctx, *x, sr.at("radius"), 1e-4, 1e3);
      if (const json* x = sr.take("wallThickness"))
        wall = attribute(ctx, *x, sr.at("wallThickness"), 1e-5, 1e3);
      if (const json* x = sr.take("waterLevel"))
        water = attribute(ctx, *x, sr.at("waterLevel"), 0, 1e3);
      const json* file = sr.take("file");
      const json* generate = sr.take("generate");
      std::string layer;
      if (const json* x = sr.take("layer")) layer = string(ctx, *x, sr.at("layer"));
      float depth = -1.0f;
      if (const json* x = sr.take("depth")) {
        depth = float(number(ctx, *x, sr.at("depth"), 0, 1e4));
        if (!(depth > 0.0f)) ctx.fail(sr.at("depth"), "a shaft's depth must be greater than 0");
      }
      sr.finish();
      if (!!file == !!generate)
        ctx.fail(r.at("shafts"),
                 "shafts need exactly one of \"file\" (a point layer) or \"generate\"");
      if (generate) {
        const std::string what = oneOf(ctx, *generate, sr.at("generate"), {"junctions", "nodes"});
        if (!radius.field.empty() || !wall.field.empty() || !water.field.empty())
          ctx.fail(r.at("shafts"), "generated shafts have no attribute fields: give constants");
        if (!(wall.constant < radius.constant))
          ctx.fail(sr.at("wallThickness"),
                   "the shafts' wall thickness must be less than their radius");
        sd.radius = float(radius.constant), sd.wallThickness = float(wall.constant);
        sd.waterLevel = float(water.constant);
        sd.ends = what == "nodes";
        addJunctionShafts(net, sd, groundAt);
      } else {
        GisImportOptions gis = gisImportOptions(ctx.geo);
        gis.layer = layer;
        for (const Attribute* at : {&radius, &wall, &water})
          if (!at->field.empty() && std::find(gis.attributes.begin(), gis.attributes.end(),
                                              at->field) == gis.attributes.end())
            gis.attributes.push_back(at->field);
        GisPoints points;
        try {
          points = importGisPoints(ctx.baseDir / string(ctx, *file, sr.at("file")), gis);
        } catch (const Error& err) {
          ctx.fail(sr.at("file"), err.what());
        }
        for (const GisPoint& q : points.points) {
          const auto get = [&](const Attribute& at) {
            return value(ctx, at, gis.attributes, q.attributes, sr.at("file"), q.featureId);
          };
          Shaft s;
          const glm::vec3 p = GeoFrame::toScene(q.position);
          s.radius = float(get(radius));
          s.wallThickness = float(get(wall));
          if (!(s.wallThickness < s.radius))
            ctx.fail(sr.at("file"), "shaft feature " + std::to_string(q.featureId) +
                                        ": wall thickness must be less than the radius");
          s.top = groundAt({p.x, p.z});
          // The floor: the point's own height where it lies under the terrain (one at or
          // above it is the cover's), else `depth` under the terrain, else under the lowest
          // pipe within the shaft.
          float bottom = s.top - depth;
          if (points.hasZ && p.y < s.top) {
            bottom = p.y;
          } else if (depth < 0) {
            bottom = s.top;
            for (const Pipe& pipe : net.pipes)
              bottom = std::min(bottom, lowestWithin(pipe, {p.x, p.z}, s.radius) - pipe.radius);
            if (bottom >= s.top)
              ctx.fail(sr.at("file"), "shaft feature " + std::to_string(q.featureId) +
                                          " meets no pipe under the terrain and has no height "
                                          "below it: give \"depth\"");
          }
          if (!(bottom < s.top)) {  // a depth too small for floats at the terrain's height
            std::ostringstream where;
            where << "shaft feature " << q.featureId << ": its floor (height " << bottom
                  << ") lies at or above the terrain there (" << s.top << ")";
            ctx.fail(sr.at("file"), where.str());
          }
          s.bottom = glm::vec3(p.x, bottom, p.z);
          s.waterLevel = float(std::clamp(get(water), 0.0, double(s.top - bottom)));
          net.shafts.push_back(s);
        }
      }
    }
    r.finish();
    trimAtShafts(net);

    // The meshes the network adds to the object list.
    const int index = int(scene.networks.size());
    const auto add = [&](NetworkPart part, Mesh mesh) {
      if (!mesh.triangles.empty())
        scene.objects.push_back(networkObject(net, index, part, std::move(mesh)));
    };
    if (!net.shafts.empty())
      for (const bool inner : {false, true})
        scene.objects.push_back(shaftObject(net, index, inner));
    add(NetworkPart::Joints, jointMesh(joints));
    if (net.mode == PipeNetwork::Mode::Mesh) add(NetworkPart::MeshedPipes, pipeMesh(net));
    scene.networks.push_back(std::move(net));
  }
}

}  // namespace cutaway::json_reader
