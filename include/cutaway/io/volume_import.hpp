// cutaway/io/volume_import.hpp — scalar volumes from NIfTI-1/-2 (.nii, .nii.gz), NumPy (.npy,
// .npz), VolPack density files (.den), MetaImage (.mha, .mhd), NRRD (.nrrd, .nhdr), VTK legacy
// structured points (.vtk), DICOM series (a folder of single-frame slices) and raw voxels
// described by a JSON header (.json).
//
// The format is chosen by the file name's suffix, case-insensitively, or a folder for DICOM.
// Values become floats in the file's units (NIfTI's scl_slope/scl_inter, DICOM's rescale
// applied). Scanner formats are placed in RAS+ millimetres, NIfTI's world: NIfTI from the
// sform, else the qform, else pixdim; MetaImage, DICOM (patient position and orientation, slices
// sorted along their normal) and NRRD's LPS/LAS spaces turned from LPS/LAS to RAS. VTK, .npy,
// .npz and .den place voxel (i, j, k) at origin + spacing·(i, j, k) as they give them (the
// identity when they give none), as does a JSON header. A 4-D NIfTI series yields its first
// volume. Every malformed, truncated or oversized file is a cutaway::Error naming the file,
// a place in it ("header", a JSON pointer, an .npz member) and the reason; nothing is
// allocated from a size the file claims before it has been checked against VolumeLimits.
//
//   cutaway::Volume head = cutaway::importVolume("/usr/share/mricron/templates/ch2.nii.gz");
//   glm::vec4 centre = head.indexToWorld * glm::vec4(glm::vec3(head.dims / 2), 1.0f);  // mm
//
// A raw volume's JSON header (the raw path relative to the JSON file's folder):
//
//   {"file": "head.raw", "dims": [256, 256, 109], "type": "u16", "spacing": [1, 1, 1.5],
//    "origin": [0, 0, 0], "endianness": "big", "headerBytes": 0}
//
// "type" is one of u8, i8, u16, i16, u32, i32, f32, f64; spacing (default 1, 1, 1), origin
// (default 0, 0, 0), endianness (default little) and headerBytes (bytes to skip, default 0)
// are optional; any other key is an error.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "cutaway/geometry/volume.hpp"

namespace cutaway {

struct VolumeLimits {
  // Larger volumes are refused before anything is allocated: 2³⁰ voxels are 4 GiB of floats.
  std::size_t maxVoxels = std::size_t(1) << 30;
};

// Throws cutaway::Error(file, place, reason) on any bad input.
Volume importVolume(const std::filesystem::path& file);
Volume importVolume(const std::filesystem::path& file, const VolumeLimits& limits);

// Voxels held in memory (a NumPy array seen through the Python module): element (i, j, k) lies
// at data + i·strides[0] + j·strides[1] + k·strides[2] bytes (strides may be negative), of the
// type `kind` ('u', 'i' or 'f') and `bytes`, byte-swapped when `swapped`.
struct MemoryVoxels {
  const void* data = nullptr;
  std::int64_t dims[3] = {0, 0, 0};
  std::int64_t strides[3] = {0, 0, 0};
  char kind = 'f';
  int bytes = 4;
  bool swapped = false;
  glm::dmat4 indexToWorld{1.0};
};
// Copies them into a Volume after checking the type, the dims and the transform as a file's
// header is checked; errors name `source` and `place`.
Volume volumeFromMemory(const MemoryVoxels& voxels, const std::string& source,
                        const std::string& place, const VolumeLimits& limits = {});

}  // namespace cutaway
