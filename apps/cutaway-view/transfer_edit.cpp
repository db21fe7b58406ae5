#include "transfer_edit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cutaway::view {

namespace {

// The open interval between neighbours' values: the next representable value (or label) past
// each.
float above(float v, bool whole) {
  return whole ? v + 1.0f : std::nextafter(v, std::numeric_limits<float>::infinity());
}
float below(float v, bool whole) {
  return whole ? v - 1.0f : std::nextafter(v, -std::numeric_limits<float>::infinity());
}

}  // namespace

int insertTransferPoint(std::vector<TransferPoint>& row, float value, float opacity, bool labels) {
  if (labels) value = std::round(value);
  const auto at = std::lower_bound(row.begin(), row.end(), value,
                                   [](const TransferPoint& p, float v) { return p.value < v; });
  if (at != row.end() && at->value == value) return -1;
  TransferPoint p = TransferFunction{{{0.0f, row}}}.at(value);
  p.value = value;
  p.opacity = std::clamp(opacity, 0.0f, 1.0f);
  const auto index = at - row.begin();
  row.insert(at, p);
  return int(index);
}

void moveTransferPoint(std::vector<TransferPoint>& row, std::size_t i, float value, float opacity,
                       bool labels) {
  if (labels) value = std::round(value);
  if (i > 0) value = std::max(value, above(row[i - 1].value, labels));
  if (i + 1 < row.size()) value = std::min(value, below(row[i + 1].value, labels));
  // Neighbours one label apart leave no room: the point stays.
  if ((i > 0 && value <= row[i - 1].value) || (i + 1 < row.size() && value >= row[i + 1].value))
    value = row[i].value;
  row[i].value = value;
  row[i].opacity = std::clamp(opacity, 0.0f, 1.0f);
}

bool removeTransferPoint(std::vector<TransferPoint>& row, std::size_t i) {
  if (row.size() < 2 || i >= row.size()) return false;
  row.erase(row.begin() + std::ptrdiff_t(i));
  return true;
}

int insertTransferRow(TransferFunction& tf, float gradient) {
  gradient = std::max(gradient, 0.0f);
  const auto at =
      std::lower_bound(tf.rows.begin(), tf.rows.end(), gradient,
                       [](const TransferFunction::Row& r, float g) { return r.gradient < g; });
  if (at != tf.rows.end() && at->gradient == gradient) return -1;
  TransferFunction::Row row = at == tf.rows.begin() ? *at : *(at - 1);
  row.gradient = gradient;
  const auto index = at - tf.rows.begin();
  tf.rows.insert(at, std::move(row));
  return int(index);
}

void setTransferRowGradient(TransferFunction& tf, std::size_t i, float gradient) {
  gradient = std::max(gradient, 0.0f);
  if (i > 0) gradient = std::max(gradient, above(tf.rows[i - 1].gradient, false));
  if (i + 1 < tf.rows.size()) gradient = std::min(gradient, below(tf.rows[i + 1].gradient, false));
  if ((i > 0 && gradient <= tf.rows[i - 1].gradient) ||
      (i + 1 < tf.rows.size() && gradient >= tf.rows[i + 1].gradient))
    gradient = tf.rows[i].gradient;
  tf.rows[i].gradient = gradient;
}

bool removeTransferRow(TransferFunction& tf, std::size_t i) {
  if (tf.rows.size() < 2 || i >= tf.rows.size()) return false;
  tf.rows.erase(tf.rows.begin() + std::ptrdiff_t(i));
  return true;
}

}  // namespace cutaway::view
