// SPDX-License-Identifier: MIT
#include "runnel/io/georeference_h5.hpp"

#include "runnel/core/error.hpp"

namespace runnel {

void write_georeference(H5File& f, const std::string& group, const Heightmap& t) {
  if (!t.georef.crs_wkt.empty()) f.attribute(group, "crs_wkt", t.georef.crs_wkt);
  if (t.georef.nodata) f.attribute(group, "nodata", *t.georef.nodata);
  if (!t.georef.holes.empty())  // where the source had NODATA (1), filled to run
    f.write(group + "/nodata_holes",
            std::vector<std::int32_t>(t.georef.holes.begin(), t.georef.holes.end()),
            {static_cast<hsize_t>(t.ny), static_cast<hsize_t>(t.nx)});
}

void read_georeference(const H5File& f, const std::string& path, const std::string& group,
                       Heightmap& t) {
  if (f.has_attribute(group, "crs_wkt"))
    t.georef.crs_wkt = f.read_string_attribute(group, "crs_wkt");
  if (f.has_attribute(group, "nodata")) t.georef.nodata = f.read_double_attribute(group, "nodata");
  if (f.exists(group + "/nodata_holes")) {
    t.georef.holes.clear();
    for (std::int32_t v : f.read_int32(group + "/nodata_holes",
                                       {static_cast<hsize_t>(t.ny), static_cast<hsize_t>(t.nx)})) {
      if (v != 0 && v != 1) throw input_error(path + ": " + group + "/nodata_holes is not 0 or 1");
      t.georef.holes.push_back(static_cast<std::uint8_t>(v));
    }
  }
}

}  // namespace runnel
