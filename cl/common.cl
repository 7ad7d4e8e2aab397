// SPDX-License-Identifier: MIT
// Shared helpers for every runnel kernel: counter-based random numbers (the same functions as
// src/runnel/core/rng.hpp, bit for bit), grid indexing, work-group scans, the lane types and
// the reassociation pragma.

// Lets the vectoriser reassociate a pass's sums (8 or 16 candidates at a time). The order is still
// fixed by the code, so results stay bitwise reproducible on one device. clang 12's pragma; other
// compilers (NVIDIA's knows only `clang fp contract`) keep the order as written.
#if defined(__clang_major__) && __clang_major__ >= 12 && !defined(__NV_CL_C_VERSION)
#define REASSOCIATE_SUMS _Pragma("clang fp reassociate(on)")
#else
#define REASSOCIATE_SUMS
#endif

// Exclusive prefix sum of in[0, count) into out (which may be in) by one work-group (`sums`: a
// uint per work-item and one more): each work-item sums a contiguous segment, one scans the
// segments' sums, each writes its segment's prefixes. Integer sums: a serial scan's result whatever
// the group's size (1 on a CPU, where one thread walking the table is fastest; hundreds on a GPU,
// where one thread would take milliseconds). Returns the total to every work-item.
inline uint group_exclusive_scan(const __global uint* in, __global uint* out, const uint count, __local uint* sums) {
  const uint item = get_local_id(0), items = get_local_size(0);
  const uint per = (count + items - 1) / items;
  const uint begin = min(item * per, count), end = min(begin + per, count);
  uint total = 0;
  for (uint k = begin; k < end; ++k) total += in[k];
  sums[item] = total;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (item == 0) {
    uint sum = 0;
    for (uint k = 0; k < items; ++k) {
      const uint v = sums[k];
      sums[k] = sum;
      sum += v;
    }
    sums[items] = sum;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  uint sum = sums[item];
  for (uint k = begin; k < end; ++k) {
    const uint v = in[k];
    out[k] = sum;
    sum += v;
  }
  return sums[items];
}

// Inclusive prefix sum of every work-item's `value` across the work-group (Hillis–Steele in
// `sums`, a uint per work-item); returns the work-item's own, and leaves the group's total in
// sums[size − 1] for every work-item to read. A caller that calls again must let every work-item
// read that total first (a barrier).
inline uint group_inclusive_sum(uint value, __local uint* sums) {
  const uint item = get_local_id(0), items = get_local_size(0);
  sums[item] = value;
  for (uint step = 1; step < items; step *= 2) {
    barrier(CLK_LOCAL_MEM_FENCE);
    const uint before = item >= step ? sums[item - step] : 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    sums[item] += before;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  return sums[item];
}

// splitmix64 finaliser: a bijective 64-bit mix.
inline ulong splitmix64(ulong z) {
  z += 0x9E3779B97F4A7C15UL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9UL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBUL;
  return z ^ (z >> 31);
}

// Random bits as a pure function of (seed, stream, counter): independent of thread scheduling.
inline ulong rng_bits(ulong seed, ulong stream, ulong counter) {
  return splitmix64(seed ^ splitmix64(stream ^ splitmix64(counter)));
}

// Uniform in [0, 1) with 24 random bits.
inline float rng_uniform(ulong seed, ulong stream, ulong counter) {
  return (float)(rng_bits(seed, stream, counter) >> 40) * (1.0f / 16777216.0f);
}

// A pass's numbers per cell under a host-made key (rng.hpp's rng_key): 32-bit arithmetic only.
inline uint mix32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  return x ^ (x >> 16);
}

inline float keyed_uniform(ulong key, uint counter) {
  const uint bits = mix32(mix32(counter ^ (uint)key) ^ (uint)(key >> 32));
  return (float)(bits >> 8) * (1.0f / 16777216.0f);
}

// Inlined always: PoCL keeps some large functions that two kernels call (the neighbour passes' boundary
// terms) as calls, and inlined they run faster (docs/performance.md). Clang's attribute (PoCL is
// clang); another compiler takes a plain inline.
#if defined(__clang__)
#define ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define ALWAYS_INLINE inline
#endif

// Lanes: kernels whose work-item takes LANES items (droplets, particles) in the lanes of OpenCL
// vectors, where written for one item they would run one lane at a time: the compilers of CPUs
// (PoCL's among them) do not vectorise branchy code or loops of varying length across work-items.
// The host sets LANES per device (ComputeContext::lanes(): 4, 8 or 16); every lane computes alone,
// so the results are the same bits at every width.
//
// The width fits the target's registers (a float vector fills them), so float and int lane vectors
// pass to any call as the target's ABI expects; long lane vectors are twice as wide. PoCL compiles
// with `-Dinline=`, so every helper and every builtin (convert_*, vload*, select, min) is a call
// when clang checks the calling convention, and a vector wider than the target's registers
// crossing a call changes the x86 ABI, which clang reports as a warning for every such call. So
// no helper takes or returns a lane vector by value (helpers take them through pointers, gathers
// are macros), and a long lane vector meets builtins only in halves (the *_LONGV macros) and
// otherwise operators (?:, comparisons, arithmetic), which are no calls.
#if LANES != 4 && LANES != 8 && LANES != 16
#error "LANES must be 4, 8 or 16"
#endif
#define LANE_PASTE_(a, b) a##b
#define LANE_PASTE(a, b) LANE_PASTE_(a, b)
#define LANE_VECTOR(name) LANE_PASTE(name, LANES)
typedef LANE_VECTOR(float) floatv;
typedef LANE_VECTOR(int) intv;
typedef LANE_VECTOR(long) longv;
typedef LANE_VECTOR(uint) uintv;
#define LOADV(offset, p) LANE_VECTOR(vload)(offset, p)
#define STOREV(v, offset, p) LANE_VECTOR(vstore)(v, offset, p)
#define CONVERT_FLOATV LANE_VECTOR(convert_float)
#define CONVERT_INTV LANE_VECTOR(convert_int)
#define CONVERT_LONGV LANE_VECTOR(convert_long)
#define CONVERT_UINTV LANE_VECTOR(convert_uint)

// The lanes' numbers, and the values of p at the lanes' indices k (k: a named intv).
#if LANES == 4
#define HALF_LANES 2
#define LANE_INDEX ((intv)(0, 1, 2, 3))
#define LANE_GATHER(p, k) (p[k.s0], p[k.s1], p[k.s2], p[k.s3])
#elif LANES == 8
#define HALF_LANES 4
#define LANE_INDEX ((intv)(0, 1, 2, 3, 4, 5, 6, 7))
#define LANE_GATHER(p, k) (p[k.s0], p[k.s1], p[k.s2], p[k.s3], p[k.s4], p[k.s5], p[k.s6], p[k.s7])
#else
#define HALF_LANES 8
#define LANE_INDEX ((intv)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#define LANE_GATHER(p, k)                                                                                            \
  (p[k.s0], p[k.s1], p[k.s2], p[k.s3], p[k.s4], p[k.s5], p[k.s6], p[k.s7], p[k.s8], p[k.s9], p[k.sa], p[k.sb],     \
   p[k.sc], p[k.sd], p[k.se], p[k.sf])
#endif
#define GATHER_LONG(p, k) ((longv)LANE_GATHER(p, k))
#define GATHER_FLOAT(p, k) ((floatv)LANE_GATHER(p, k))
#define GATHER_UINT(p, k) ((uintv)LANE_GATHER(p, k))

// Long lane vectors through builtins in halves (each a float lane vector's bits), lane by lane the
// same values as the whole-vector builtins.
#define HALF_VECTOR(name) LANE_PASTE(name, HALF_LANES)
#define LONGV_TO_FLOATV(v) ((floatv)(HALF_VECTOR(convert_float)((v).lo), HALF_VECTOR(convert_float)((v).hi)))
#define LONGV_TO_INTV(v) ((intv)(HALF_VECTOR(convert_int)((v).lo), HALF_VECTOR(convert_int)((v).hi)))
#define FLOATV_TO_LONGV(f) ((longv)(HALF_VECTOR(convert_long)((f).lo), HALF_VECTOR(convert_long)((f).hi)))
#define INTV_TO_LONGV(i) ((longv)(HALF_VECTOR(convert_long)((i).lo), HALF_VECTOR(convert_long)((i).hi)))
#define LOADV_LONG(offset, p) ((longv)(HALF_VECTOR(vload)(2 * (offset), p), HALF_VECTOR(vload)(2 * (offset) + 1, p)))
#define STOREV_LONG(v, offset, p)                       \
  do {                                                  \
    HALF_VECTOR(vstore)((v).lo, 2 * (offset), p);       \
    HALF_VECTOR(vstore)((v).hi, 2 * (offset) + 1, p);   \
  } while (0)
// select(a, b, mask), max and min of long lane vectors as operators; the mask a longv of 0 or −1.
#define SELECT_LONGV(a, b, mask) ((mask) ? (b) : (a))
#define MAX_LONGV(a, b) ((a) > (b) ? (a) : (b))
#define MIN_LONGV(a, b) ((a) < (b) ? (a) : (b))

inline int grid_index(int i, int j, int nx) { return j * nx + i; }

// Row of cell k in rows of nx cells, without an integer division (which does not vectorise across
// work-items): the float estimate is off by at most one for any grid below 2^20 rows, and the
// selects correct it exactly. (An int2 of column and row would be worse: a vector value in a
// work-item stops PoCL's vectoriser.)
inline int grid_row(int k, int nx) {
  const int j = (int)((float)k * (1.0f / (float)nx));
  const int i = k - j * nx;
  return i < 0 ? j - 1 : (i >= nx ? j + 1 : j);
}

// Terrain tiles of TERRAIN_TILE × TERRAIN_TILE vertices (DeviceTerrain). A kernel that adds to the
// terrain's deltas marks the tiles of the vertices it touched, so that applying a step's changes and
// refreshing the normals cost what the water touched, not the whole terrain. Every marker writes the
// same 1, so concurrent marks agree.
#define TERRAIN_TILE_SHIFT 4
#define TERRAIN_TILE (1 << TERRAIN_TILE_SHIFT)

inline int terrain_tile(int i, int j, int tiles_x) {
  return (j >> TERRAIN_TILE_SHIFT) * tiles_x + (i >> TERRAIN_TILE_SHIFT);
}

// The contact surface (terrain_sample.cl) is the terrain with every vertex raised by r / n_y (r a
// particle's radius, n_y the vertex normal's vertical part, bounded below so a near-vertical cliff
// does not lift it without limit). One expression for the samplers and for the normals kernel,
// which keeps the raised heights of the SPH contact radius beside the normals.
#define CONTACT_MIN_NY 0.2f
inline float raised_height(float height, float normal_y, float radius) {
  return height + radius / fmax(normal_y, CONTACT_MIN_NY);
}

// The float view (DeviceTerrain's `height`) of a fixed-point height: high and low bits apart,
// accurate to a float's rounding.
inline float fixed_height_view(long h, float quantum) {
  const long high = h >> 20;  // arithmetic shift: floor division by 2^20, also for negative heights
  const long low = h - (high << 20);
  return (float)high * (quantum * 1048576.0f) + (float)low * quantum;
}

// Marks the tiles of the vertices [i0, i1] × [j0, j1] (inside the grid).
inline void mark_changed_tiles(__global uint* changed, int tiles_x, int i0, int i1, int j0, int j1) {
  for (int tj = j0 >> TERRAIN_TILE_SHIFT; tj <= j1 >> TERRAIN_TILE_SHIFT; ++tj)
    for (int ti = i0 >> TERRAIN_TILE_SHIFT; ti <= i1 >> TERRAIN_TILE_SHIFT; ++ti) changed[tj * tiles_x + ti] = 1u;
}

// The ground's per-vertex factors (cl/ground.cl, docs/layers.md), for the kernels that erode or
// rain: compiled with GROUND = 0 or RAIN_MASK = 0 they are the constant 1, and the field is never read.
#ifndef GROUND
#define GROUND 0
#endif
#ifndef RAIN_MASK
#define RAIN_MASK 0
#endif
#define ERODIBILITY(field, k) (GROUND ? (field)[k] : 1.0f)
#define RAIN_WEIGHT(field, k) (RAIN_MASK ? (field)[k] : 1.0f)

// What a bed of loose sediment (quanta) over rock gives for a detachment `demand` (quanta at
// erodibility 1) in one step: the sediment first, at its erodibility, and once it is gone the rock,
// at the rock's, for the rest of the step (docs/layers.md). Equal erodibilities give demand·e exactly.
inline float bed_detachment(float demand, float sediment, float e_sediment, float e_rock) {
  if (e_sediment == e_rock || sediment <= 0.0f) return demand * e_rock;
  const float from_sediment = demand * e_sediment;
  if (from_sediment <= sediment) return from_sediment;
  return sediment + (demand - sediment / e_sediment) * e_rock;
}
#if GROUND
#define BED_DETACHMENT(demand, k) \
  bed_detachment((demand), (float)ground_sediment[k], sediment_erodibility[k], rock_erodibility[k])
#else
#define BED_DETACHMENT(demand, k) (demand)
#endif
