// Edits of a volume's transfer function by the viewer's editor (panels/transfer_panel.cpp),
// each keeping what the scene file requires of it (docs/scene-format.md, volumes): values
// strictly increasing in a row (whole values in a label volume's), opacity and importance in
// [0, 1], at least one point per row, rows at strictly increasing gradient magnitudes. The
// renderer takes an edited function in its next frame (kinds/volumes: VolumeKind).
#pragma once

#include <cstddef>
#include <vector>

#include "cutaway/scene/scene.hpp"

namespace cutaway::view {

// Inserts a point at `value` with `opacity`, with the colour and importance the row has there;
// its index, or nothing (-1) where the row has a point at that value already.
int insertTransferPoint(std::vector<TransferPoint>& row, float value, float opacity,
                        bool labels = false);
// Moves point i to `value`, kept between its neighbours, and `opacity`, clamped to [0, 1].
void moveTransferPoint(std::vector<TransferPoint>& row, std::size_t i, float value, float opacity,
                       bool labels = false);
// Removes point i unless it is the row's only one; whether it did.
bool removeTransferPoint(std::vector<TransferPoint>& row, std::size_t i);

// Adds a row at gradient magnitude `gradient`, a copy of the row below it (or above, at the
// start): a one-dimensional function becomes two-dimensional. Its index, or -1 where a row has
// that gradient already.
int insertTransferRow(TransferFunction& tf, float gradient);
// Sets row i's gradient magnitude, kept between its neighbours' (and ≥ 0).
void setTransferRowGradient(TransferFunction& tf, std::size_t i, float gradient);
// Removes row i unless it is the only one; whether it did.
bool removeTransferRow(TransferFunction& tf, std::size_t i);

}  // namespace cutaway::view
