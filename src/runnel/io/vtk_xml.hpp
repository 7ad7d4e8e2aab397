// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace runnel {

// One array of a VTK XML file: its name, VTK type (Float32, Float64, Int32, UInt32, Int64), its
// components and its bytes as they lie in memory (little-endian).
struct VtkArray {
  std::string name;
  const char* type;
  int components;
  const void* data;
  std::size_t bytes;
};

// A section of a VTK XML piece (PointData, Points, Verts) with the attributes of its tag and its
// arrays.
struct VtkSection {
  std::string tag, attributes;
  std::vector<VtkArray> arrays;
};

// Writes a VTK XML file of one piece (`type` PolyData or StructuredGrid, the dataset's and the
// piece's attributes as XML), its arrays as raw appended binary with UInt64 headers: the format
// ParaView's default readers open with every array. Atomic: a failed write leaves no file.
void write_vtk_xml(const std::string& path, const std::string& type,
                   const std::string& dataset_attributes, const std::string& piece_attributes,
                   const std::vector<VtkSection>& sections);

}  // namespace runnel
