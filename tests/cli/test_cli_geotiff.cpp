// SPDX-License-Identifier: MIT
// GeoTIFF through the runnel binary, checked with GDAL's own tools: the input is made by
// gdal_translate from the shipped real DEM with a projected CRS, and what runnel writes is read
// back by gdalinfo, so the georeferencing is judged by GDAL, not by runnel's reader.
#include <gtest/gtest.h>

#include <cmath>

#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::run_cli;
using test::run_program;
using test::ScratchDir;

bool have_gdal_tools() {
  return run_program("gdalinfo", {"--version"}).exit_code == 0 &&
         run_program("gdal_translate", {"--version"}).exit_code == 0;
}

// The text of a JSON value in `json` after "KEY": up to its end (an array's ']' or a string's
// closing quote), as gdalinfo -json printed it: enough to compare two files' values exactly.
std::string json_field(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return "<no " + key + ">";
  std::size_t start = json.find_first_not_of(" \n", at + key.size() + 3);
  std::size_t end = start;
  if (json[start] == '[') {
    end = json.find(']', start) + 1;
  } else if (json[start] == '"') {
    end = start + 1;
    while (end < json.size() && !(json[end] == '"' && json[end - 1] != '\\')) ++end;
    ++end;
  } else {
    end = json.find_first_of(",\n}", start);
  }
  std::string value = json.substr(start, end - start);
  std::erase_if(value, [](char c) { return c == ' ' || c == '\n'; });
  return value;
}

struct GdalInfo {
  std::string size, transform, wkt, nodata;
};

GdalInfo gdalinfo(const std::string& path) {
  const auto r = run_program("gdalinfo", {"-json", path});
  EXPECT_EQ(r.exit_code, 0) << path << ": " << r.err;
  return {json_field(r.out, "size"), json_field(r.out, "geoTransform"), json_field(r.out, "wkt"),
          json_field(r.out, "noDataValue")};
}

// The shipped real DEM (ESRI ASCII, 83 m cells, NODATA -9999) as a GeoTIFF in UTM zone 16N.
std::string projected_dem(const ScratchDir& dir) {
  const std::string tif = dir.path("jacksboro_utm.tif");
  const auto r = run_program(
      "gdal_translate",
      {"-q", "-a_srs", "EPSG:32616", "-a_ullr", "700000", "4000000", "733449", "3971448",
       "-a_nodata", "-9999", test::source_dir() + "/data/terrains/jacksboro_fault_dem.asc", tif});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return tif;
}

TEST(CliGeoTiff, ConvertKeepsTheCrsTransformAndNodataAsGdalSeesThem) {
  if (!have_gdal_tools())
    GTEST_SKIP() << "gdalinfo/gdal_translate not installed (scripts/setup.sh)";
  ScratchDir dir;
  const std::string input = projected_dem(dir);
  const GdalInfo in = gdalinfo(input);
  ASSERT_NE(in.wkt.find("UTMzone16N"), std::string::npos) << in.wkt;

  ASSERT_EQ(run_cli({"convert", input, dir.path("copy.tif")}).exit_code, 0);
  const GdalInfo copy = gdalinfo(dir.path("copy.tif"));
  EXPECT_EQ(copy.size, in.size);
  EXPECT_EQ(copy.transform, in.transform);
  EXPECT_EQ(copy.wkt, in.wkt);
  EXPECT_EQ(copy.nodata, in.nodata);

  // ASC holds the corner and the cell size (not the CRS): GDAL reads the same transform from it,
  // and a GeoTIFF made back from it has the transform again.
  ASSERT_EQ(run_cli({"convert", input, dir.path("copy.asc")}).exit_code, 0);
  EXPECT_EQ(gdalinfo(dir.path("copy.asc")).transform, in.transform);
  ASSERT_EQ(run_cli({"convert", dir.path("copy.asc"), dir.path("back.tif")}).exit_code, 0);
  EXPECT_EQ(gdalinfo(dir.path("back.tif")).transform, in.transform);

  // The heights themselves, float for float.
  const Heightmap a = read_terrain(input), b = read_terrain(dir.path("copy.tif"));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a.h[k], b.h[k]) << k;
  EXPECT_EQ(b.georef.nodata, std::optional<double>(-9999.0));
}

TEST(CliGeoTiff, AProjectedDemRunsAndItsOutputsOverlayTheInput) {
  if (!have_gdal_tools())
    GTEST_SKIP() << "gdalinfo/gdal_translate not installed (scripts/setup.sh)";
  ScratchDir dir;
  const std::string input = projected_dem(dir);
  const GdalInfo in = gdalinfo(input);
  const auto r = run_cli({"run", "--terrain", input, "--model", "pipe", "--steps", "40", "--out",
                          dir.path("run"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"final.tif", "erosion.tif"}) {
    const GdalInfo out = gdalinfo(dir.path("run/" + std::string(name)));
    EXPECT_EQ(out.size, in.size) << name;
    EXPECT_EQ(out.transform, in.transform) << name;
    EXPECT_EQ(out.wkt, in.wkt) << name;
  }
  // erosion.tif is final − initial, vertex by vertex; the checkpoint carries the CRS too.
  const Heightmap initial = read_terrain(input),
                  final_terrain = read_terrain(dir.path("run/final.tif"));
  const Heightmap change = read_terrain(dir.path("run/erosion.tif"));
  double moved = 0;
  for (std::size_t k = 0; k < change.size(); ++k) {
    ASSERT_NEAR(change.h[k], final_terrain.h[k] - initial.h[k], 1e-4) << k;
    moved += std::fabs(change.h[k]);
  }
  EXPECT_GT(moved, 0.0) << "the run eroded something";
  const auto info = run_cli({"info", dir.path("run/final.h5")});
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("UTM zone 16N"), std::string::npos) << info.out;
  const auto json = run_cli({"info", dir.path("run/final.h5"), "--json"});
  EXPECT_NE(json.out.find("\"crs\": \"WGS 84 / UTM zone 16N\""), std::string::npos) << json.out;
  EXPECT_EQ(test::json_number(json.out, "origin_x"), 700000.0);
}

TEST(CliGeoTiff, RastersRunnelCannotUseAreRefusedWithOneLine) {
  if (!have_gdal_tools())
    GTEST_SKIP() << "gdalinfo/gdal_translate not installed (scripts/setup.sh)";
  ScratchDir dir;
  const std::string dem = test::source_dir() + "/data/terrains/jacksboro_fault_dem.asc";
  struct Case {
    std::vector<std::string> translate;
    std::string name, expected;
  };
  const std::vector<Case> cases = {
      {{"-a_srs", "EPSG:4326", "-a_ullr", "-84.5", "36.5", "-84.1", "36.2"},
       "geographic.tif",
       "UTM zone of its centre: gdalwarp -t_srs EPSG:32616"},
      // South of the equator and east of Greenwich: the zone is the centre's, not a fixed one.
      {{"-a_srs", "EPSG:4326", "-a_ullr", "150.0", "-33.0", "150.4", "-33.3"},
       "sydney.tif",
       "EPSG:32756"},
      {{"-a_srs", "EPSG:32616", "-a_ullr", "700000", "4000000", "740300", "3971448"},
       "rectangular.tif",
       "not square"},
      {{"-a_srs", "EPSG:2274", "-a_ullr", "700000", "4000000", "733449", "3971448"},
       "feet.tif",
       "not metres"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"-q"};
    args.insert(args.end(), c.translate.begin(), c.translate.end());
    args.push_back(dem);
    args.push_back(dir.path(c.name));
    ASSERT_EQ(run_program("gdal_translate", args).exit_code, 0) << c.name;
    const auto r = run_cli({"info", dir.path(c.name)});
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.name), std::string::npos) << "names the file: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  // A rotated geotransform, written as GDAL's own virtual raster.
  ASSERT_EQ(run_program("gdal_translate",
                        {"-q", "-of", "VRT", "-a_srs", "EPSG:32616", dem, dir.path("north_up.vrt")})
                .exit_code,
            0);
  std::string vrt = test::read_text(dir.path("north_up.vrt"));
  const std::size_t start = vrt.find("<GeoTransform>"), end = vrt.find("</GeoTransform>");
  ASSERT_NE(start, std::string::npos);
  vrt.replace(start, end - start, "<GeoTransform>700000, 80, 20, 4000000, 20, -80");
  test::write_text(dir.path("rotated.vrt"), vrt);
  const auto r = run_cli({"info", dir.path("rotated.vrt")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("rotated"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace runnel
