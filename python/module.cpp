// The Python module's native part (`cutaway._cutaway`): scenes loaded from files or JSON text,
// options set by their scene-file paths, renderers on a headless OpenGL context shared by all
// of them and released with the last, frames and AOVs as NumPy arrays, cutaway::Error as
// cutaway.Error. python/cutaway/__init__.py wraps it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <string_view>
#include <type_traits>
#include <unordered_set>

#include "cutaway/core/contained.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/geometry/mesh.hpp"
#include "cutaway/gl/context.hpp"
#include "cutaway/io/volume_import.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "cutaway/scene/scene.hpp"

namespace py = pybind11;
using namespace cutaway;

namespace {

// The one headless context of the process, made when the first renderer needs it and
// destroyed when the last renderer that holds it goes away; and the process that made the
// first (0: none yet).
std::weak_ptr<gl::HeadlessContext> sharedContext;
pid_t contextProcess = 0;

// OpenGL does not survive fork(): the driver's threads stay in the parent, and the child's
// first OpenGL call waits for them forever. Nor does the driver's state once the last context
// is gone (llvmpipe keeps its screen and threads): a child of any process that made one is
// refused.
void checkNotForked() {
  if (contextProcess != 0 && ::getpid() != contextProcess)
    throw Error(
        "this process was forked from one that made a cutaway renderer, and the OpenGL "
        "driver does not survive fork(): make renderers only after forking, or use "
        "multiprocessing's \"spawn\" or \"forkserver\" start method");
}

std::shared_ptr<gl::HeadlessContext> context() {
  checkNotForked();
  if (auto c = sharedContext.lock()) return c;
  std::shared_ptr<gl::HeadlessContext> c = gl::HeadlessContext::create();
  c->release();  // made current on each call instead (OnThisThread)
  sharedContext = c, contextProcess = ::getpid();
  return c;
}

// OpenGL work from whichever Python thread calls: the context is current on the calling
// thread for the call and released after it, since EGL lets one thread at a time hold it
// (the GIL, held throughout, keeps the calls apart).
class OnThisThread {
 public:
  explicit OnThisThread(const gl::HeadlessContext& context) : context_(context) {
    checkNotForked();
    context_.makeCurrent();
  }
  ~OnThisThread() { context_.release(); }
  OnThisThread(const OnThisThread&) = delete;
  OnThisThread& operator=(const OnThisThread&) = delete;

 private:
  const gl::HeadlessContext& context_;
};

class PyRenderer;
// The renderers __init__ made: one from Renderer.__new__ alone has none, and its methods
// would run on unset memory.
std::unordered_set<const PyRenderer*> madeRenderers;

// A renderer with its own copy of the scene (cutaway::Renderer keeps a reference to it) and
// a share of the context. The context is declared first, so it outlives the renderer.
class PyRenderer {
 public:
  explicit PyRenderer(const Scene& scene) : context_(context()), scene_(scene) {
    const OnThisThread current(*context_);
    renderer_ = std::make_unique<Renderer>(scene_, context_->info());
    madeRenderers.insert(this);
  }
  ~PyRenderer() {
    madeRenderers.erase(this);
    if (::getpid() != contextProcess) {
      // A copy in a forked child: the parent's OpenGL objects, and its context, are not this
      // process's to free; both are left as they are (a leak, not a hang).
      (void)renderer_.release();
      new std::shared_ptr<gl::HeadlessContext>(std::move(context_));
      return;
    }
    const OnThisThread current(*context_);
    renderer_.reset();
  }
  PyRenderer(const PyRenderer&) = delete;
  PyRenderer& operator=(const PyRenderer&) = delete;

  py::array_t<std::uint8_t> render(float time) {
    // The scene's times, as `cutaway render --time` takes them.
    if (!(time >= 0.0f && time <= 1e6f))
      throw Error("render", "time", "expected seconds in [0, 1e6], got " + std::to_string(time));
    const OnThisThread current(*context_);
    renderer_->renderAt(time);
    rendered_ = true;
    const Rgba8Image image = renderer_->readColor();
    py::array_t<std::uint8_t> out({image.height, image.width, 4});
    std::memcpy(out.mutable_data(), image.pixels.data(), image.pixels.size());
    return out;
  }

  // Every AOV of the last frame: float32 arrays, rows top to bottom, (H, W) for one channel.
  py::dict aovs() const {
    requireFrame("aovs");
    const OnThisThread current(*context_);
    py::dict out;
    for (const Aov& a : renderer_->readAovs()) out[py::str(a.name)] = toArray(a.image);
    return out;
  }

  py::list timings() {
    requireFrame("timings");
    const OnThisThread current(*context_);
    py::list out;
    for (const PassTiming& t : renderer_->timings()) {
      py::dict d;
      d["name"] = t.name;
      d["gpu_ms"] = t.gpuMs;
      d["cpu_ms"] = t.cpuMs;
      out.append(d);
    }
    return out;
  }

  const std::string& device() const { return context_->info().renderer; }

 private:
  static py::array_t<float> toArray(const FloatImage& image) {
    std::vector<py::ssize_t> shape{image.height, image.width};
    if (image.channels > 1) shape.push_back(image.channels);
    py::array_t<float> out(shape);
    std::memcpy(out.mutable_data(), image.data.data(), image.data.size() * sizeof(float));
    return out;
  }

  void requireFrame(const char* what) const {
    if (!rendered_) throw Error(what, "", "no frame yet: call render() first");
  }

  std::shared_ptr<gl::HeadlessContext> context_;
  Scene scene_;
  std::unique_ptr<Renderer> renderer_;
  bool rendered_ = false;
};

// `h` as a NumPy array: of T's dtype and C-contiguous (a copy where it must be), or for void
// as it is (its own dtype and layout, no copy of an array); none where NumPy cannot make one
// (a TypeError or ValueError: the caller names the argument). Any other error (a MemoryError,
// a KeyboardInterrupt) is raised as it is: py::array::ensure() cleared them all, and a copy
// too large for memory was reported as a shape.
template <class T = void>
std::optional<py::array> asArray(const py::handle& h) {
  const py::module_ numpy = py::module_::import("numpy");
  try {
    if constexpr (std::is_void_v<T>)
      return py::array(numpy.attr("asarray")(h));
    else
      return py::array(numpy.attr("ascontiguousarray")(h, py::dtype::of<T>()));
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_TypeError) && !e.matches(PyExc_ValueError)) throw;
    return std::nullopt;
  }
}

// `r`, if __init__ made it.
template <class R>
R& made(R* r) {
  if (!madeRenderers.contains(r))
    throw py::type_error("this Renderer was not made by Renderer(scene)");
  return *r;
}

// A mesh from arrays: `vertices` (N, 3) in object space, `faces` (M, 3) indices into them
// (counter-clockwise seen from outside), checked as a mesh file's are; normals as the mesh
// importer makes them. Errors name `source` and `place`.
std::shared_ptr<const Mesh> meshFromArrays(const std::string& source, const std::string& place,
                                           const py::handle& vertexArray,
                                           const py::handle& faceArray) {
  const auto fail = [&](const std::string& reason) { throw Error(source, place, reason); };
  // The kinds first: the conversion would take 0.5 as index 0, a complex number as its real part
  // and 2⁶³ as −2⁶³.
  const auto kind = [](const py::handle& h) {
    const std::optional<py::array> a = asArray(h);
    return a ? a->dtype().kind() : '?';
  };
  const char vertexKind = kind(vertexArray), faceKind = kind(faceArray);
  if (std::string_view("iuf").find(vertexKind) == std::string_view::npos)
    fail("vertices must be real numbers of shape (N, 3)");
  const std::optional<py::array> vertices = asArray<double>(vertexArray);
  if (!vertices || vertices->ndim() != 2 || vertices->shape(1) != 3)
    fail("vertices must be real numbers of shape (N, 3)");
  if (faceKind != 'i' && faceKind != 'u') fail("faces must be integers of shape (M, 3)");
  Mesh mesh;
  const auto* v = static_cast<const double*>(vertices->data());
  for (py::ssize_t i = 0; i < vertices->shape(0); ++i) {
    const glm::dvec3 p(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    if (!(std::abs(p.x) <= 1e15 && std::abs(p.y) <= 1e15 && std::abs(p.z) <= 1e15))
      fail("vertex " + std::to_string(i) + " is not finite or lies beyond 1e15");
    mesh.positions.emplace_back(p);
  }
  // Signed indices read as signed (−1 stays −1), unsigned as unsigned (2⁶³ stays 2⁶³).
  const auto addFaces = [&](auto index) {
    using Index = decltype(index);
    const auto outside = [](Index v, Index count) {
      if constexpr (std::is_signed_v<Index>)
        return v < 0 || v >= count;
      else
        return v >= count;
    };
    const std::optional<py::array> faces = asArray<Index>(faceArray);
    if (!faces || faces->ndim() != 2 || faces->shape(1) != 3)
      fail("faces must be integers of shape (M, 3)");
    const auto* f = static_cast<const Index*>(faces->data());
    const auto count = Index(mesh.positions.size());
    for (py::ssize_t i = 0; i < faces->shape(0); ++i) {
      for (int k = 0; k < 3; ++k)
        if (outside(f[3 * i + k], count))
          fail("face " + std::to_string(i) + " has vertex index " + std::to_string(f[3 * i + k]) +
               " out of range (" + std::to_string(count) + " vertices)");
      mesh.triangles.emplace_back(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
    }
  };
  if (faceKind == 'u')
    addFaces(std::uint64_t{});
  else
    addFaces(std::int64_t{});
  mesh.report.droppedDegenerate = dropDegenerateTriangles(mesh);
  if (mesh.triangles.empty()) fail("no triangle of non-zero area");
  computeVertexNormals(mesh);
  mesh.report.normalsComputed = true;
  analyzeTopology(mesh);
  orientOutward(mesh);
  return std::make_shared<const Mesh>(std::move(mesh));
}

// A volume from a 3-D array indexed values[i, j, k], any layout and byte order, and the
// row-major 4×4 `affine` from voxel index to world (NiBabel's convention). Errors name `source`
// and `place`.
std::shared_ptr<const Volume> volumeFromArray(const std::string& source, const std::string& place,
                                              const py::array& values,
                                              const std::array<double, 16>& affine) {
  if (values.ndim() != 3)
    throw Error(source, place,
                "values must be a 3-D array, got " + std::to_string(values.ndim()) + " dimensions");
  MemoryVoxels voxels;
  voxels.data = values.data();
  for (int a = 0; a < 3; ++a) {
    voxels.dims[a] = values.shape(a);
    voxels.strides[a] = values.strides(a);
  }
  const py::dtype type = values.dtype();
  voxels.kind = type.kind();
  voxels.bytes = int(type.itemsize());
  const char order = type.byteorder();
  voxels.swapped = (order == '>' && std::endian::native == std::endian::little) ||
                   (order == '<' && std::endian::native == std::endian::big);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) voxels.indexToWorld[c][r] = affine[std::size_t(4 * r + c)];
  return std::make_shared<const Volume>(volumeFromMemory(voxels, source, place));
}

// Meshes {key: (vertices, faces)} and volumes {key: (values, affine)} for "arrays": KEY.
SceneArrays sceneArrays(const std::string& source, const py::dict& meshes,
                        const py::dict& volumes) {
  SceneArrays arrays;
  for (const auto& [key, value] : meshes) {
    const auto name = key.cast<std::string>();
    const auto pair = value.cast<py::tuple>();
    arrays.meshes[name] = meshFromArrays(source, name, pair[0], pair[1]);
  }
  for (const auto& [key, value] : volumes) {
    const auto name = key.cast<std::string>();
    const auto pair = value.cast<py::tuple>();
    arrays.volumes[name] = volumeFromArray(source, name, pair[0].cast<py::array>(),
                                           pair[1].cast<std::array<double, 16>>());
  }
  return arrays;
}

// The role of a scene file's name.
Role roleNamed(const std::string& source, const std::string& place, const std::string& name) {
  if (const std::optional<Role> r = roleFromName(name)) return *r;
  throw Error(
      source, place,
      "unknown role " + quote(name) + " (expected one of: context, interest, exterior, interior)");
}

// Applies `change` to a copy of the scene, checks the copy as a scene file is checked (the
// names, the reach, the cutters' roles), and only then keeps it.
template <class Change>
auto changeChecked(Scene& s, const std::string& source, Change change) {
  Scene changed = s;
  auto result = change(changed);
  checkScene(changed, source);
  s = std::move(changed);
  return result;
}

// `f()`, its errors led by the method's name, as the module's own are ("set_role: …").
template <class F>
auto calledAs(const char* method, F f) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(method, "", e.what());
  }
}

// An object from arrays, appended to the scene with a role and an optional colour.
void addMesh(Scene& s, const std::string& name, const py::handle& vertices, const py::handle& faces,
             const std::string& role, const std::optional<std::array<float, 3>>& color) {
  const auto fail = [&](const std::string& reason) { throw Error("add_mesh", name, reason); };
  if (name.empty()) fail("the object needs a name");
  SceneObject o;
  o.name = name;
  o.source = "numpy";
  o.role = roleNamed("add_mesh", name, role);
  if (color) o.material.color = glm::vec3((*color)[0], (*color)[1], (*color)[2]);
  o.mesh = meshFromArrays("add_mesh", name, vertices, faces);
  changeChecked(s, "add_mesh", [&](Scene& changed) {
    changed.objects.push_back(std::move(o));
    return 0;
  });
}

}  // namespace

PYBIND11_MODULE(_cutaway, m) {
  m.doc() = "cutaway's native part; use the cutaway package";
  // The file readers' helper, forked now rather than after the session has grown
  // (cutaway/core/contained.hpp).
  cutaway::startContainedHelper();
  // cutaway::Error as cutaway.Error, its message decoded with backslash escapes where it is
  // not UTF-8 (a file's bytes quoted), not left empty.
  static const py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const Error& e) {
      const std::string_view what = e.what();
      const py::object text = py::reinterpret_steal<py::object>(
          PyUnicode_DecodeUTF8(what.data(), py::ssize_t(what.size()), "backslashreplace"));
      PyErr_SetObject(error.ptr(), text.ptr());
    }
  });

  // Scenes come from load() and parse() alone: an instance from Scene.__new__ would hold no
  // scene, and pybind11 would read one from unset memory.
  py::class_<Scene>(m, "Scene", py::custom_type_setup([](PyHeapTypeObject* type) {
                      type->ht_type.tp_new = [](PyTypeObject*, PyObject*, PyObject*) -> PyObject* {
                        PyErr_SetString(PyExc_TypeError,
                                        "a cutaway.Scene is made by cutaway.load() or "
                                        "cutaway.from_dict()");
                        return nullptr;
                      };
                    }))
      .def_static("load", &loadScene, py::arg("path"), "A scene file (docs/scene-format.md)")
      .def_static(
          "parse",
          [](const std::string& text, const std::string& name, const std::filesystem::path& dir,
             const py::dict& meshes, const py::dict& volumes) {
            return parseScene(text, name, dir, sceneArrays(name, meshes, volumes));
          },
          py::arg("text"), py::arg("name"), py::arg("base_dir"), py::arg("meshes") = py::dict(),
          py::arg("volumes") = py::dict(),
          "Scene JSON text; relative file names resolve against base_dir; entries with "
          "\"arrays\": KEY take meshes[KEY] = (vertices, faces) or volumes[KEY] = (values, "
          "affine)")
      .def(
          "_set_text",
          [](Scene& s, const std::string& path, const std::string& value) {
            setOption(s, path, value);
          },
          py::arg("path"), py::arg("value"),
          "Any technique's option by its scene-file path, the value as --set writes it")
      .def(
          "_add_volume",
          [](Scene& s, const std::string& text, const std::string& key, const py::array& values,
             const std::array<double, 16>& affine) {
            SceneArrays arrays;
            arrays.volumes[key] = volumeFromArray("add_volume", key, values, affine);
            appendVolume(s, text, "add_volume", ".", arrays);
          },
          py::arg("text"), py::arg("key"), py::arg("values"), py::arg("affine"),
          "A \"volumes\" entry whose \"arrays\" is `key`")
      .def("add_mesh", &addMesh, py::arg("name"), py::arg("vertices"), py::arg("faces"),
           py::arg("role") = "context", py::arg("color") = py::none(),
           "An object from arrays: vertices (N, 3), faces (M, 3) indices")
      .def(
          "set_importance",
          [](Scene& s, const std::string& pattern, float importance) {
            return calledAs("set_importance", [&] { return s.setImportance(pattern, importance); });
          },
          py::arg("pattern"), py::arg("importance"),
          "Importance in [0, 1] for the objects whose name or group the pattern matches whole; "
          "returns how many")
      .def(
          "set_role",
          [](Scene& s, const std::string& pattern, const std::string& role) {
            const Role r = roleNamed("set_role", pattern, role);
            return changeChecked(s, "set_role", [&](Scene& changed) {
              return calledAs("set_role", [&] { return changed.setRole(pattern, r); });
            });
          },
          py::arg("pattern"), py::arg("role"),
          "The role (context, interest, exterior, interior) of the objects whose name or group "
          "and the volumes whose name the pattern matches whole; returns how many")
      .def_property_readonly("width", [](const Scene& s) { return s.width; })
      .def_property_readonly("height", [](const Scene& s) { return s.height; })
      .def_property_readonly("samples", [](const Scene& s) { return s.samples; })
      .def_property_readonly("pixel_error", [](const Scene& s) { return s.pixelError; })
      .def_property_readonly("objects",
                             [](const Scene& s) {
                               std::vector<std::string> names;
                               for (const SceneObject& o : s.objects) names.push_back(o.name);
                               return names;
                             })
      .def_property_readonly("volumes", [](const Scene& s) {
        std::vector<std::string> names;
        for (const SceneVolume& v : s.volumes) names.push_back(v.name);
        return names;
      });

  py::class_<PyRenderer>(m, "Renderer")
      .def(py::init<const Scene&>(), py::arg("scene"),
           "Compiles the scene's frame on the shared headless context (the scene is copied)")
      .def(
          "render", [](PyRenderer* r, float time) { return made(r).render(time); },
          py::arg("time") = 0.0f,
          "One frame at `time` seconds: RGBA uint8, shape (height, width, 4), rows top down")
      .def(
          "aovs", [](const PyRenderer* r) { return made(r).aovs(); },
          "The last frame's AOVs by name (float32 arrays)")
      .def(
          "timings", [](PyRenderer* r) { return made(r).timings(); },
          "The last frame's passes: name, gpu_ms, cpu_ms")
      .def_property_readonly(
          "device", [](const PyRenderer* r) { return made(r).device(); },
          "The OpenGL renderer string");

  m.def(
      "live_contexts", [] { return sharedContext.expired() ? 0 : 1; },
      "1 while a renderer holds the headless context, else 0");
}
