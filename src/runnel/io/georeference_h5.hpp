// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/core/heightmap.hpp"
#include "runnel/io/hdf5_file.hpp"

namespace runnel {

// A terrain's georeference in an HDF5 group (checkpoints' /terrain, series' /grid): the CRS as OGC
// WKT (attribute crs_wkt), the source's NODATA value (attribute nodata) and its holes (dataset
// nodata_holes, ny × nx, 1 where the source had NODATA); each absent when the terrain has none.
void write_georeference(H5File& f, const std::string& group, const Heightmap& terrain);
// Reads them back into `terrain.georef` (whose grid is already sized); `path` names the file in
// errors.
void read_georeference(const H5File& f, const std::string& path, const std::string& group,
                       Heightmap& terrain);

}  // namespace runnel
