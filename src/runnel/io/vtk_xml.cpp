// SPDX-License-Identifier: MIT
#include "runnel/io/vtk_xml.hpp"

#include <bit>
#include <cstdint>
#include <cstdio>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"

namespace runnel {

void write_vtk_xml(const std::string& path, const std::string& type,
                   const std::string& dataset_attributes, const std::string& piece_attributes,
                   const std::vector<VtkSection>& sections) {
  static_assert(std::endian::native == std::endian::little,
                "the appended data is written as it lies in memory");
  // Each array's block in the appended data: its byte count (UInt64), then its bytes.
  std::size_t offset = 0;
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"" + type +
                    "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<" +
                    type + (dataset_attributes.empty() ? "" : " " + dataset_attributes) +
                    ">\n<Piece " + piece_attributes + ">\n";
  for (const VtkSection& s : sections) {
    xml += "<" + s.tag + (s.attributes.empty() ? "" : " " + s.attributes) + ">\n";
    for (const VtkArray& a : s.arrays) {
      xml += "<DataArray type=\"" + std::string(a.type) + "\" Name=\"" + a.name +
             "\" NumberOfComponents=\"" + std::to_string(a.components) +
             "\" format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
      offset += sizeof(std::uint64_t) + a.bytes;
    }
    xml += "</" + s.tag + ">\n";
  }
  xml += "</Piece>\n</" + type + ">\n<AppendedData encoding=\"raw\">\n_";
  write_file_atomically(path, [&](std::FILE* f) {
    std::fwrite(xml.data(), 1, xml.size(), f);
    for (const VtkSection& s : sections)
      for (const VtkArray& a : s.arrays) {
        const std::uint64_t bytes = a.bytes;
        std::fwrite(&bytes, sizeof bytes, 1, f);
        if (bytes > 0) std::fwrite(a.data, 1, a.bytes, f);
      }
    std::fputs("\n</AppendedData>\n</VTKFile>\n", f);
    if (std::ferror(f)) throw runtime_error(path + ": write failed");
  });
}

}  // namespace runnel
