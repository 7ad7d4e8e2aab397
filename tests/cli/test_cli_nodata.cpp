// SPDX-License-Identifier: MIT
// A terrain with NODATA holes refused on request: the message names the scenario key and the flag
// that fill them, and following it works.
#include <gtest/gtest.h>

#include <gdal.h>

#include "runnel/io/images.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

// A 20 x 20 ramp with one NODATA hole, at column 7 of row 9.
void write_holed_terrain(const std::string& path) {
  std::string asc =
      "ncols 20\nnrows 20\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n";
  for (int j = 0; j < 20; ++j) {
    for (int i = 0; i < 20; ++i) asc += (i == 7 && j == 9) ? "-9999 " : std::to_string(i + j) + " ";
    asc += "\n";
  }
  test::write_text(path, asc);
}

// The value GDAL reads at (column, row) of a raster, and whether GDAL calls it NODATA.
std::pair<double, bool> gdal_value(const std::string& path, int column, int row) {
  GDALAllRegister();
  GDALDatasetH d = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!d) return {0, false};
  GDALRasterBandH band = GDALGetRasterBand(d, 1);
  int has_nodata = 0;
  const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
  double v = 0;
  const CPLErr e = GDALRasterIO(band, GF_Read, column, row, 1, 1, &v, 1, 1, GDT_Float64, 0, 0);
  GDALClose(d);
  return {v, e == CE_None && has_nodata && v == nodata};
}

// Pixels of an RGB PNG in the NODATA colour (read by GDAL's PNG driver).
long nodata_pixels(const std::string& path) {
  GDALAllRegister();
  GDALDatasetH d = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!d || GDALGetRasterCount(d) < 3) return -1;
  const int w = GDALGetRasterXSize(d), h = GDALGetRasterYSize(d);
  std::vector<std::uint8_t> band[3];
  for (int b = 0; b < 3; ++b) {
    band[b].resize(static_cast<std::size_t>(w) * h);
    if (GDALRasterIO(GDALGetRasterBand(d, b + 1), GF_Read, 0, 0, w, h, band[b].data(), w, h,
                     GDT_Byte, 0, 0) != CE_None)
      return -1;
  }
  GDALClose(d);
  long n = 0;
  for (std::size_t k = 0; k < band[0].size(); ++k)
    n += band[0][k] == kNodataColour[0] && band[1][k] == kNodataColour[1] &&
         band[2][k] == kNodataColour[2];
  return n;
}

TEST(CliNodata, HolesComeBackAsNodataInEveryRasterAndTheMetricsLeaveThemOut) {
  test::ScratchDir dir;
  write_holed_terrain(dir.path("holes.asc"));
  const auto r = test::run_cli({"run", "--terrain", dir.path("holes.asc"), "--model", "thermal",
                                "--set", "run.iterations=3", "--quiet", "--out", dir.path("run")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* raster : {"final.tif", "final.asc", "erosion.tif"}) {
    EXPECT_TRUE(gdal_value(dir.path("run/" + std::string(raster)), 7, 9).second)
        << raster << ": the hole is NODATA again";
    EXPECT_FALSE(gdal_value(dir.path("run/" + std::string(raster)), 8, 9).second)
        << raster << ": its neighbour is data";
  }
  // A checkpoint keeps the holes: its export writes them back too.
  const auto e = test::run_cli(
      {"export", dir.path("run/final.h5"), "--format", "tif", "-o", dir.path("export.tif")});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_TRUE(gdal_value(dir.path("export.tif"), 7, 9).second);
  // And runnel reads its own output's hole as a hole.
  const Heightmap back = read_terrain(dir.path("run/final.tif"));
  ASSERT_EQ(back.georef.holes.size(), back.h.size());
  EXPECT_EQ(back.georef.holes[9 * 20 + 7], 1);
  EXPECT_EQ(std::count(back.georef.holes.begin(), back.georef.holes.end(), 1), 1);
  // NPY's hole is NaN: the final heights and the drainage area, NaN there and only there.
  for (const char* npy : {"final.npy", "drainage_area.npy"}) {
    const Heightmap raw = read_npy(dir.path("run/" + std::string(npy)), 1.0, NodataPolicy::kFill);
    EXPECT_EQ(raw.georef.holes, back.georef.holes) << npy;
  }
  // The pictures draw the hole in the NODATA colour (a vertex's share of the picture, zoom² pixels)
  // rather than the heights the fill invented, and name the colour.
  const int zoom = picture_zoom(back);
  for (const char* png : {"height_initial.png", "height_final.png", "erosion.png"}) {
    const long n = nodata_pixels(dir.path("run/" + std::string(png)));
    EXPECT_GE(n, static_cast<long>(zoom / 2) * (zoom / 2)) << png;
    EXPECT_LE(n, static_cast<long>(zoom + 1) * (zoom + 1) + 2000) << png << ": the hole alone";
  }
}

TEST(CliNodata, TheRefusalNamesTheKeyThatFillsTheHolesAndTheKeyWorks) {
  test::ScratchDir dir;
  write_holed_terrain(dir.path("holes.asc"));
  const std::vector<std::string> run = {"run",     "--terrain", dir.path("holes.asc"), "--model",
                                        "thermal", "--set",     "run.iterations=1",    "--quiet"};
  auto refuse = run;
  refuse.insert(refuse.end(), {"--set", "terrain.nodata=\"refuse\"", "--out", dir.path("a")});
  const auto r = test::run_cli(refuse);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("1 NODATA cells"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("terrain.nodata = \"fill\""), std::string::npos) << r.err;
  auto fill = run;
  fill.insert(fill.end(), {"--set", "terrain.nodata=\"fill\"", "--out", dir.path("b")});
  const auto f = test::run_cli(fill);
  EXPECT_EQ(f.exit_code, 0) << f.err;
  // runnel convert names its own flag, which exists.
  const auto c =
      test::run_cli({"convert", dir.path("holes.asc"), dir.path("c.npy"), "--nodata", "refuse"});
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_NE(c.err.find("--nodata fill"), std::string::npos) << c.err;
  EXPECT_EQ(test::run_cli({"convert", dir.path("holes.asc"), dir.path("d.npy"), "--nodata", "fill"})
                .exit_code,
            0);
}

}  // namespace
}  // namespace runnel
