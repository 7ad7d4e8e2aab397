// SPDX-License-Identifier: MIT
// Runs collide_segment (collide.cl) on given segments, so tests can compare it with a brute-force
// search over every triangle.

// `surface`: the vertex heights of the mesh to hit (the terrain's, or DeviceTerrain's contact surface).
__kernel void collide_probe(const __global float* segments, const uint n, const __global float* surface,
                            const __global float* terrain_normal, const int tnx, const int tny, const float tcell,
                            __global float* result) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float3 o = vload3(2 * i, segments), d = vload3(2 * i + 1, segments);
  const TerrainHit hit = collide_segment(surface, terrain_normal, tnx, tny, tcell, o, d);
  result[4 * i] = hit.t;
  result[4 * i + 1] = hit.normal.x;
  result[4 * i + 2] = hit.normal.y;
  result[4 * i + 3] = hit.normal.z;
}
