// SPDX-License-Identifier: MIT
// Readers and writers of every terrain format: round trips, and every malformed input gives its
// one-line input error (exit code 2) naming the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "runnel/core/error.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::ScratchDir;
using test::write_text;

Heightmap sample_terrain() {
  return generate_terrain("fbm", 37, 23, 2.5, 11);
}

// Expects `f` to throw an input error whose message names `file` and contains `fragment`.
template <typename F>
void expect_input_error(F f, const std::string& file, const std::string& fragment) {
  try {
    f();
    FAIL() << "no error for " << file;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
  }
}

TEST(TerrainIo, AscRoundTripIsExact) {
  ScratchDir dir;
  Heightmap t = sample_terrain();
  t.origin_x = 1234.5;
  t.origin_z = -17.25;
  write_terrain(dir.path("t.asc"), t);
  const Heightmap r = read_terrain(dir.path("t.asc"));
  EXPECT_EQ(r.nx, t.nx);
  EXPECT_EQ(r.ny, t.ny);
  EXPECT_DOUBLE_EQ(r.cell, t.cell);
  EXPECT_DOUBLE_EQ(r.origin_x, t.origin_x);
  EXPECT_DOUBLE_EQ(r.origin_z, t.origin_z);
  EXPECT_EQ(0, std::memcmp(r.h.data(), t.h.data(), t.h.size() * sizeof(float)));
}

TEST(TerrainIo, NpyRoundTripIsExact) {
  ScratchDir dir;
  const Heightmap t = sample_terrain();
  write_terrain(dir.path("t.npy"), t);
  ReadOptions options;
  options.cell = t.cell;
  const Heightmap r = read_terrain(dir.path("t.npy"), options);
  ASSERT_EQ(r.nx, t.nx);
  ASSERT_EQ(r.ny, t.ny);
  EXPECT_EQ(0, std::memcmp(r.h.data(), t.h.data(), t.h.size() * sizeof(float)));
  // The file is what NumPy writes: magic, version 1.0, header padded to 64 bytes.
  const std::string bytes = test::read_text(dir.path("t.npy"));
  EXPECT_EQ(bytes.substr(0, 6), "\x93NUMPY");
  const std::size_t header_len =
      static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
  EXPECT_EQ((10 + header_len) % 64, 0u);
  EXPECT_EQ(bytes.size(), 10 + header_len + t.size() * 4);
}

// Writes a .npy by hand, so the reader is tested on layouts runnel itself never writes.
void write_npy_raw(const std::string& path, const std::string& descr, bool fortran, int rows,
                   int cols, const std::string& data) {
  std::string header = "{'descr': '" + descr +
                       "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': (" +
                       std::to_string(rows) + ", " + std::to_string(cols) + "), }";
  header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  std::string bytes = "\x93NUMPY";
  bytes += '\x01';
  bytes += '\x00';
  bytes += static_cast<char>(header.size() & 0xff);
  bytes += static_cast<char>(header.size() >> 8);
  write_text(path, bytes + header + data);
}

TEST(TerrainIo, NpyReadsFloat64FortranAndBigEndian) {
  ScratchDir dir;
  // A 2 x 3 array [[0,1,2],[10,11,12]] in three encodings.
  const double rows[2][3] = {{0, 1, 2}, {10, 11, 12}};
  std::string f8c, f8f, f4be;
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 3; ++c) f8c.append(reinterpret_cast<const char*>(&rows[r][c]), 8);
  }
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 2; ++r) f8f.append(reinterpret_cast<const char*>(&rows[r][c]), 8);
  }
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 3; ++c) {
      const float v = static_cast<float>(rows[r][c]);
      char b[4];
      std::memcpy(b, &v, 4);
      std::swap(b[0], b[3]);
      std::swap(b[1], b[2]);
      f4be.append(b, 4);
    }
  }
  write_npy_raw(dir.path("c.npy"), "<f8", false, 2, 3, f8c);
  write_npy_raw(dir.path("f.npy"), "<f8", true, 2, 3, f8f);
  write_npy_raw(dir.path("be.npy"), ">f4", false, 2, 3, f4be);
  for (const char* name : {"c.npy", "f.npy", "be.npy"}) {
    const Heightmap t = read_terrain(dir.path(name));
    ASSERT_EQ(t.nx, 3) << name;
    ASSERT_EQ(t.ny, 2) << name;
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(t.at(c, r), rows[r][c]) << name << " " << r << "," << c;
    }
  }
}

TEST(TerrainIo, Png16RoundTripWithinQuantisation) {
  ScratchDir dir;
  const Heightmap t = sample_terrain();
  write_terrain(dir.path("t.png"), t);
  const Heightmap r =
      read_terrain(dir.path("t.png"));  // range and cell come from the file's text chunks
  ASSERT_EQ(r.nx, t.nx);
  ASSERT_EQ(r.ny, t.ny);
  EXPECT_DOUBLE_EQ(r.cell, t.cell);
  const double quantum = (t.max_height() - t.min_height()) / 65535.0;
  for (std::size_t k = 0; k < t.size(); ++k) ASSERT_NEAR(r.h[k], t.h[k], 0.5 * quantum + 1e-4) << k;
  EXPECT_FLOAT_EQ(r.min_height(), t.min_height());
  EXPECT_FLOAT_EQ(r.max_height(), t.max_height());
}

TEST(TerrainIo, PngGivenRangeOverridesStoredOne) {
  ScratchDir dir;
  Heightmap t(3, 2, 1.0);
  t.h = {0, 50, 100, 25, 75, 100};
  write_png16(dir.path("t.png"), t, HeightRange{0, 100});
  const Heightmap r = read_png16(dir.path("t.png"), HeightRange{1000, 1200});
  EXPECT_NEAR(r.at(1, 0), 1100.0, 0.01);
  EXPECT_NEAR(r.at(0, 1), 1050.0, 0.01);
}

TEST(TerrainIo, AscNodataIsFilledOrRefused) {
  ScratchDir dir;
  write_text(dir.path("holes.asc"),
             "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n"
             "1 2 3\n4 -9999 6\n7 8 9\n");
  const Heightmap filled = read_asc(dir.path("holes.asc"), NodataPolicy::kFill);
  EXPECT_FLOAT_EQ(filled.at(1, 1), 5.0f);  // mean of its 8 neighbours
  expect_input_error([&] { read_asc(dir.path("holes.asc"), NodataPolicy::kRefuse); }, "holes.asc",
                     "NODATA");
  write_text(dir.path("allholes.asc"),
             "ncols 2\nnrows 2\ncellsize 1\nNODATA_value -1\n-1 -1\n-1 -1\n");
  expect_input_error([&] { read_asc(dir.path("allholes.asc"), NodataPolicy::kFill); },
                     "allholes.asc", "every cell");
}

TEST(TerrainIo, AscAcceptsCellCentreHeader) {
  ScratchDir dir;
  write_text(dir.path("c.asc"),
             "NCOLS 2\nNROWS 2\nXLLCENTER 5\nYLLCENTER 5\nCELLSIZE 10\n1 2\n3 4\n");
  const Heightmap t = read_terrain(dir.path("c.asc"));
  EXPECT_DOUBLE_EQ(t.origin_x, 0.0);
  EXPECT_FLOAT_EQ(t.at(1, 1), 4.0f);
}

TEST(TerrainIo, MalformedAscGivesOneLineErrors) {
  ScratchDir dir;
  const std::string header = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
  struct Case {
    const char* name;
    std::string text;
    const char* fragment;
  } cases[] = {
      {"truncated.asc", header + "1 2 3\n4 5\n", "truncated"},
      {"nonnumeric.asc", header + "1 2 3\n4 five 6\n", "non-numeric"},
      {"nan.asc", header + "1 2 3\n4 nan 6\n", "not a finite number"},
      {"inf.asc", header + "1 inf 3\n4 5 6\n", "not a finite number"},
      {"extra.asc", header + "1 2 3\n4 5 6\n7\n", "more values"},
      {"noheader.asc", "1 2 3\n4 5 6\n", "missing header key"},
      {"nocell.asc", "ncols 3\nnrows 2\n1 2 3\n4 5 6\n", "cellsize"},
      {"badcell.asc", "ncols 3\nnrows 2\ncellsize -1\n1 2 3\n4 5 6\n", "cellsize -1 is outside"},
      {"badkey.asc", "ncols 3\nnrows 2\ncellsize 1\nbogus 4\n1 2 3\n4 5 6\n", "bogus"},
      {"fractional.asc", "ncols 2.5\nnrows 2\ncellsize 1\n1 2 3\n4 5 6\n", "integers"},
      {"huge.asc", "ncols 100000\nnrows 100000\ncellsize 1\n1\n", "exceeds the limit"},
      {"tiny.asc", "ncols 1\nnrows 1\ncellsize 1\n1\n", "too small"},
      {"empty.asc", "", "empty file"},
  };
  for (auto& c : cases) {
    write_text(dir.path(c.name), c.text);
    expect_input_error([&] { read_terrain(dir.path(c.name)); }, c.name, c.fragment);
  }
}

TEST(TerrainIo, MalformedPngAndNpyGiveOneLineErrors) {
  ScratchDir dir;
  const Heightmap t = sample_terrain();
  write_terrain(dir.path("good.png"), t);
  write_terrain(dir.path("good.npy"), t);
  const std::string png = test::read_text(dir.path("good.png"));
  const std::string npy = test::read_text(dir.path("good.npy"));
  write_text(dir.path("truncated.png"), png.substr(0, png.size() / 2));
  write_text(dir.path("text.png"), "this is not a png at all");
  write_text(dir.path("truncated.npy"), npy.substr(0, npy.size() - 7));
  write_text(dir.path("trailing.npy"), npy + "xx");
  write_text(dir.path("text.npy"), "ncols 3\n");
  std::string header_cut = npy.substr(0, 20);
  write_text(dir.path("headercut.npy"), header_cut);
  write_npy_raw(dir.path("int.npy"), "<i4", false, 2, 2, std::string(16, '\0'));
  write_npy_raw(dir.path("threed.npy"), "<f4", false, 2, 2, std::string(16, '\0'));
  {  // a 3-D shape
    std::string h = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2, 2), }";
    h.append((64 - (10 + h.size() + 1) % 64) % 64, ' ');
    h += '\n';
    std::string bytes = "\x93NUMPY\x01";
    bytes += '\0';
    bytes += static_cast<char>(h.size());
    bytes += '\0';
    write_text(dir.path("threed.npy"), bytes + h + std::string(32, '\0'));
  }
  const float inf = std::numeric_limits<float>::infinity();
  std::string inf_data(16, '\0');
  std::memcpy(inf_data.data() + 4, &inf, 4);
  write_npy_raw(dir.path("inf.npy"), "<f4", false, 2, 2, inf_data);

  expect_input_error([&] { read_terrain(dir.path("truncated.png")); }, "truncated.png", "PNG");
  expect_input_error([&] { read_terrain(dir.path("text.png")); }, "text.png", "not a PNG");
  expect_input_error([&] { read_terrain(dir.path("truncated.npy")); }, "truncated.npy",
                     "truncated");
  expect_input_error([&] { read_terrain(dir.path("trailing.npy")); }, "trailing.npy", "trailing");
  expect_input_error([&] { read_terrain(dir.path("text.npy")); }, "text.npy", "not a NumPy");
  expect_input_error([&] { read_terrain(dir.path("headercut.npy")); }, "headercut.npy",
                     "truncated");
  expect_input_error([&] { read_terrain(dir.path("int.npy")); }, "int.npy",
                     "not float32 or float64");
  expect_input_error([&] { read_terrain(dir.path("threed.npy")); }, "threed.npy", "3 dimensions");
  expect_input_error([&] { read_terrain(dir.path("inf.npy")); }, "inf.npy", "not a finite");
  expect_input_error([&] { read_terrain(dir.path("missing.asc")); }, "missing.asc", "no such file");
  expect_input_error([&] { read_terrain(dir.path("t.xyz")); }, "t.xyz", "unknown terrain format");
  test::write_text(dir.path("junk.tif"), "not a TIFF at all");
  expect_input_error([&] { read_terrain(dir.path("junk.tif")); }, "junk.tif",
                     "not a raster GDAL reads");
}

TEST(TerrainIo, FailedWriteLeavesTheOldFileIntact) {
  ScratchDir dir;
  write_text(dir.path("keep.asc"), "old contents");
  // A terrain the PNG writer accepts but into a folder that does not exist: nothing is created.
  EXPECT_THROW(write_terrain(dir.path("nofolder/t.asc"), sample_terrain()), Error);
  EXPECT_EQ(test::read_text(dir.path("keep.asc")), "old contents");
  // No temporary files are left behind after a successful write.
  write_terrain(dir.path("keep.asc"), sample_terrain());
  int files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir.root())) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST(TerrainIo, RealDemReadsWithItsHeader) {
  const Heightmap t = read_terrain(test::source_dir() + "/data/terrains/jacksboro_fault_dem.asc");
  EXPECT_EQ(t.nx, 403);
  EXPECT_EQ(t.ny, 344);
  EXPECT_DOUBLE_EQ(t.cell, 83.0);
  EXPECT_NEAR(t.min_height(), 236.0, 1.0);
  EXPECT_NEAR(t.max_height(), 1076.0, 1.0);
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// NPY has no NODATA value: NaN is its hole. Read, a NaN is a hole under terrain.nodata's policy
// (refused, or filled from its neighbours and remembered); written, a hole is NaN again.
TEST(TerrainIo, NpyHolesAreNanBothWays) {
  test::ScratchDir dir;
  Heightmap t(3, 2, 1.0);
  t.h = {1.0f, std::nanf(""), 3.0f, 4.0f, 5.0f, 6.0f};
  std::string data(t.h.size() * 4, '\0');
  std::memcpy(data.data(), t.h.data(), data.size());
  write_npy_raw(dir.path("holed.npy"), "<f4", false, 2, 3, data);
  ReadOptions refuse;
  refuse.nodata = NodataPolicy::kRefuse;
  expect_input_error([&] { read_terrain(dir.path("holed.npy"), refuse); }, "holed.npy",
                     "1 NODATA cells");
  const Heightmap filled = read_terrain(dir.path("holed.npy"));
  ASSERT_EQ(filled.georef.holes.size(), 6u);
  EXPECT_EQ(filled.georef.holes[1], 1);
  EXPECT_EQ(std::count(filled.georef.holes.begin(), filled.georef.holes.end(), 1), 1);
  // Filled with the mean of its valid neighbours: 1, 3, 4, 5, 6.
  EXPECT_FLOAT_EQ(filled.h[1], (1.0f + 3.0f + 4.0f + 5.0f + 6.0f) / 5.0f);
  write_terrain(dir.path("back.npy"), filled);
  const Heightmap raw = read_npy(dir.path("back.npy"), 1.0, NodataPolicy::kFill);
  EXPECT_EQ(raw.georef.holes, filled.georef.holes) << "the hole comes back as NaN";
  for (std::size_t k : {0u, 2u, 3u, 4u, 5u}) EXPECT_EQ(raw.h[k], t.h[k]) << k;
}

}  // namespace
}  // namespace runnel
