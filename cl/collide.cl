// SPDX-License-Identifier: MIT
// Continuous terrain collision (physics.md §3). A particle's step is the segment o → o + d. Its
// footprint on the (x, z) plane is walked tile by tile (2-D DDA, Amanatides & Woo 1987); each tile's
// two triangles are tested with Möller & Trumbore (1997); the earliest hit from above wins. The
// mesh is the contact surface (terrain_sample.cl), given by its vertex heights `surface`: the
// terrain raised by a particle's radius, so such a particle touches the ground with its lowest
// point (the terrain's own heights: the terrain itself). The
// response uses the vertex normals interpolated with the hit's barycentric (u, v):
//   v ← v_t − e v_n   (when v·n < 0; e the restitution), timed at the hit (integrate.cl)
// Tiles are split along the diagonal (i, j)–(i+1, j+1), as in terrain_sample.cl.
// Compile-time constants (host -D): SPH_RESTITUTION.

#define COLLIDE_MAX_TILES 65536  // bounds the walk for a corrupt (NaN, huge) segment

inline float3 contact_vertex(const __global float* surface, int i, int j, int nx, float cell) {
  return (float3)((float)i * cell, surface[j * nx + i], (float)j * cell);
}

// Möller–Trumbore: the t in [0, 1] where o + t·d crosses triangle (v0, v1, v2) from above, else −1.
inline float moller_trumbore(float3 o, float3 d, float3 v0, float3 v1, float3 v2, float* u_out, float* v_out) {
  const float3 e1 = v1 - v0;
  const float3 e2 = v2 - v0;
  const float3 p = cross(d, e2);
  const float det = dot(e1, p);
  // det = dot(e1, cross(d, e2)) = dot(d, cross(e2, e1)); the triangles are wound so that
  // cross(e2, e1) points up, so a segment going down through the face has det < 0. Parallel and
  // upward crossings are ignored.
  if (!(det < 0.0f)) return -1.0f;
  const float inv = 1.0f / det;
  const float3 s = o - v0;
  const float u = dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return -1.0f;
  const float3 q = cross(s, e1);
  const float v = dot(d, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return -1.0f;
  const float t = dot(e2, q) * inv;
  if (t < 0.0f || t > 1.0f) return -1.0f;
  *u_out = u;
  *v_out = v;
  return t;
}

typedef struct {
  float t;       // segment parameter of the hit, or −1
  float3 point;  // m
  float3 normal; // interpolated vertex normal, unit
  float3 face;   // the hit triangle's own normal, unit
} TerrainHit;

// The unit normal of triangle (v0, v1, v2), wound as the tiles' triangles are (cross(e2, e1) up).
inline float3 face_normal(float3 v0, float3 v1, float3 v2) { return normalize(cross(v2 - v0, v1 - v0)); }

inline void test_tile(const __global float* surface, const __global float* normal, int nx, float cell, int i, int j,
                      float3 o, float3 d, TerrainHit* best) {
  const float3 p00 = contact_vertex(surface, i, j, nx, cell);
  const float3 p10 = contact_vertex(surface, i + 1, j, nx, cell);
  const float3 p11 = contact_vertex(surface, i + 1, j + 1, nx, cell);
  const float3 p01 = contact_vertex(surface, i, j + 1, nx, cell);
  const int k00 = j * nx + i, k10 = k00 + 1, k11 = k00 + nx + 1, k01 = k00 + nx;
  float u, v;
  // Triangle A: (i,j), (i+1,j), (i+1,j+1); triangle B: (i,j), (i+1,j+1), (i,j+1). In this order
  // cross(e2, e1) points up for both, so a downward crossing has det < 0 (moller_trumbore).
  float t = moller_trumbore(o, d, p00, p10, p11, &u, &v);
  if (t >= 0.0f && (best->t < 0.0f || t < best->t)) {
    best->t = t;
    best->point = o + t * d;
    best->normal = normalize((1.0f - u - v) * vload3(k00, normal) + u * vload3(k10, normal) + v * vload3(k11, normal));
    best->face = face_normal(p00, p10, p11);
  }
  t = moller_trumbore(o, d, p00, p11, p01, &u, &v);
  if (t >= 0.0f && (best->t < 0.0f || t < best->t)) {
    best->t = t;
    best->point = o + t * d;
    best->normal = normalize((1.0f - u - v) * vload3(k00, normal) + u * vload3(k11, normal) + v * vload3(k01, normal));
    best->face = face_normal(p00, p11, p01);
  }
}

// The earliest crossing of the contact surface from above along o → o + d, walking the tiles under
// it.
inline TerrainHit collide_segment(const __global float* surface, const __global float* normal, int nx, int ny,
                                  float cell, float3 o, float3 d) {
  TerrainHit best;
  best.t = -1.0f;
  const float u0 = o.x / cell, v0 = o.z / cell;
  const float du = d.x / cell, dv = d.z / cell;
  int i = (int)floor(u0), j = (int)floor(v0);
  const int i_end = (int)floor(u0 + du), j_end = (int)floor(v0 + dv);
  const int step_i = du > 0.0f ? 1 : -1, step_j = dv > 0.0f ? 1 : -1;
  // Parameter t at which the footprint crosses the next tile edge in u and in v.
  const float t_delta_u = du != 0.0f ? fabs(1.0f / du) : INFINITY;
  const float t_delta_v = dv != 0.0f ? fabs(1.0f / dv) : INFINITY;
  float t_max_u = du > 0.0f ? ((float)(i + 1) - u0) / du : du < 0.0f ? (u0 - (float)i) / -du : INFINITY;
  float t_max_v = dv > 0.0f ? ((float)(j + 1) - v0) / dv : dv < 0.0f ? (v0 - (float)j) / -dv : INFINITY;
  for (int walked = 0; walked < COLLIDE_MAX_TILES; ++walked) {
    if (i >= 0 && j >= 0 && i < nx - 1 && j < ny - 1) {
      test_tile(surface, normal, nx, cell, i, j, o, d, &best);
      // Tiles are visited in order along the segment: a hit before the next edge cannot be beaten.
      if (best.t >= 0.0f && best.t <= fmin(t_max_u, t_max_v)) break;
    }
    if (i == i_end && j == j_end) break;
    if (t_max_u < t_max_v) {
      if (t_max_u > 1.0f) break;
      i += step_i;
      t_max_u += t_delta_u;
    } else {
      if (t_max_v > 1.0f) break;
      j += step_j;
      t_max_v += t_delta_v;
    }
  }
  return best;
}

// Velocity after contact with a surface of unit normal n (only when moving into it): the normal
// part reverses, scaled by the restitution e; the tangential part is kept (bed friction acts as a
// stress over time, integrate.cl, not per impact).
inline float3 contact_response(float3 v, float3 n) {
  const float vn = dot(v, n);
  if (vn >= 0.0f) return v;
  return v - ((1.0f + SPH_RESTITUTION) * vn) * n;
}

// The same against a face whose own normal is `face`: after the response along the interpolated
// normal n, whatever still moves into the face is taken away. Where the two normals differ (a
// wall's foot, a bend between steep faces) the smooth response alone can leave a velocity into the
// face that the next step's contact stops again, growing by g·dt a step in a particle that does
// not move. On a plane the two normals agree and the second step changes nothing.
inline float3 contact_response_on_face(float3 v, float3 n, float3 face) {
  const float3 out = contact_response(v, n);
#if SPH_CONTACT_FACE_NORMAL
  const float into = dot(out, face);
  return into < 0.0f ? out - into * face : out;
#else
  return out;
#endif
}

// The own normal of the contact surface's triangle under (x, z), clamped to the heightmap.
inline float3 contact_face_at(const __global float* surface, int nx, int ny, float cell, float x, float z) {
#if !SPH_CONTACT_FACE_NORMAL
  return (float3)(0.0f, 1.0f, 0.0f);  // unused: the response takes the interpolated normal alone
#endif
  const TilePoint t = tile_point(nx, ny, cell, x, z);
  const int i = t.k00 % nx, j = t.k00 / nx;
  const float3 p00 = contact_vertex(surface, i, j, nx, cell), p11 = contact_vertex(surface, i + 1, j + 1, nx, cell);
  return t.w01 == 0.0f ? face_normal(p00, contact_vertex(surface, i + 1, j, nx, cell), p11)
                       : face_normal(p00, p11, contact_vertex(surface, i, j + 1, nx, cell));
}
