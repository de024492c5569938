// One piece of a tessellation pattern (schemes/preprocess/tess_patterns.h) as the mesh shader makes
// it: which vertices a piece emits, in which order, and the triangles over them, by arithmetic on the
// factors plus the strip table. Shared by GLSL (shaders/sphere_ms.mesh) and C++, where
// tests/test_tess_patterns.cpp checks every piece against tessellateQuad triangle for triangle: the
// rules live there, this is their parallel form (any vertex and any triangle from its index alone).
//
// Layout of piece (x, y) of a k0 x k1 split: first the block of grid points a0..a1 x b0..b1 (the
// grid cells' and the strips' ring rows all lie in it), then each strip's edge points in walk order.
// A piece touching two edges holds their shared corner twice (bit-equal points: harmless), and a
// piece whose block holds more grid points than its cells and strips use emits those unused.
// Triangles: the grid cells row by row, then the strips of edges v=0, u=1, v=1, u=0, as the
// generator orders them. The includer defines LB_TESS_STEPS(p, q) (the strip table's word) and
// LB_TESS_BITCOUNT(x) first.
#ifndef LB_TESS_PIECE_H
#define LB_TESS_PIECE_H

#define LB_TESS_CAP 11                        // kTessCap
#define LB_TESS_TABLE_SIDE (LB_TESS_CAP + 1)  // strip table entry p * side + q
// The most a piece emits in this layout (tests/test_tess_patterns.cpp finds both maxima over every
// factor combination): within VK_EXT_mesh_shader's guaranteed 256 and 256.
#define LB_TESS_MAX_VERTICES 148
#define LB_TESS_MAX_TRIANGLES 242

#ifdef __cplusplus
namespace lb {
namespace tesspiece {
#define LB_TESS_FN inline
#else
#define LB_TESS_FN
#endif

struct TessPatch {
  int n[4];    // outer factors, edges u=0, v=0, u=1, v=1 (all >= 1: a culled patch has no piece)
  int m0, m1;  // inner factors as tessellated: an inner 1 counts as 2 unless all six are 1
  int k0, k1;  // the split: columns, rows
  bool allOne;
};

struct TessPiece {
  int a0, a1, b0, b1;  // the block of grid points
  int w, cells;        // grid points a row, grid cells
  bool has[4];         // a strip on edge k (with triangles)
  int e0[4], e1[4];    // its edge points, walked from e0 to e1 (the parent edge's point indices)
  int vEdge[4];        // its first edge point in the vertex list
  int tStrip[4];       // its first triangle
  int vertices, triangles;
};

struct TessFrac {  // a vertex (u, v) as fractions, never reduced
  int un, ud, vn, vd;
};

struct TessTri {
  int a, b, c;  // local vertex indices, counter-clockwise in (u, v)
};

LB_TESS_FN int tessMaxI(int a, int b) {
  return a > b ? a : b;
}
LB_TESS_FN int tessCeilDiv(int a, int b) {
  return (a + b - 1) / b;
}
// Grid line or edge point where part i of `parts` starts (Split::at).
LB_TESS_FN int tessAt(int count, int parts, int i) {
  return i * count / parts;
}
// Ring rows run over grid lines 1 .. m - 1 (Split::ringU, ringV).
LB_TESS_FN int tessRing(int m, int parts, int i) {
  int r = tessAt(m, parts, i);
  return r < 1 ? 1 : (r > m - 1 ? m - 1 : r);
}

LB_TESS_FN TessPatch tessPatch(int n0, int n1, int n2, int n3, int i0, int i1) {
  TessPatch t;
  t.n[0] = n0;
  t.n[1] = n1;
  t.n[2] = n2;
  t.n[3] = n3;
  t.m0 = tessMaxI(i0, 1);
  t.m1 = tessMaxI(i1, 1);
  t.allOne = t.m0 == 1 && t.m1 == 1 && n0 == 1 && n1 == 1 && n2 == 1 && n3 == 1;
  if (!t.allOne) {
    t.m0 = tessMaxI(t.m0, 2);
    t.m1 = tessMaxI(t.m1, 2);
  }
  t.k0 = t.allOne ? 1
                  : tessMaxI(tessCeilDiv(t.m0, LB_TESS_CAP),
                             tessMaxI(tessCeilDiv(n1, LB_TESS_CAP), tessCeilDiv(n3, LB_TESS_CAP)));
  t.k1 = t.allOne ? 1
                  : tessMaxI(tessCeilDiv(t.m1, LB_TESS_CAP),
                             tessMaxI(tessCeilDiv(n0, LB_TESS_CAP), tessCeilDiv(n2, LB_TESS_CAP)));
  return t;
}

// Ring segments of strip k: along u on edges v=0 and v=1, along v on the others.
LB_TESS_FN int tessRingSegments(TessPiece q, int k) {
  return k == 1 || k == 3 ? q.a1 - q.a0 : q.b1 - q.b0;
}
LB_TESS_FN int tessEdgeSegments(TessPiece q, int k) {
  int d = q.e1[k] - q.e0[k];
  return d < 0 ? -d : d;
}

LB_TESS_FN TessPiece tessPiece(TessPatch t, int x, int y) {
  TessPiece q;
  for (int k = 0; k < 4; ++k) {
    q.has[k] = false;
    q.e0[k] = 0;
    q.e1[k] = 0;
    q.vEdge[k] = 0;
    q.tStrip[k] = 0;
  }
  if (t.allOne) {  // the quad's two triangles over its corners
    q.a0 = q.a1 = q.b0 = q.b1 = 0;
    q.w = 1;
    q.cells = 0;
    q.vertices = 4;
    q.triangles = 2;
    return q;
  }
  q.a0 = tessRing(t.m0, t.k0, x);
  q.a1 = tessRing(t.m0, t.k0, x + 1);
  q.b0 = tessRing(t.m1, t.k1, y);
  q.b1 = tessRing(t.m1, t.k1, y + 1);
  q.w = q.a1 - q.a0 + 1;
  q.cells = (q.a1 - q.a0) * (q.b1 - q.b0);
  q.vertices = q.w * (q.b1 - q.b0 + 1);
  q.triangles = 2 * q.cells;
  // Walk directions are the generator's: v=0 along +u, u=1 along +v, v=1 along -u, u=0 along -v.
  q.e0[1] = tessAt(t.n[1], t.k0, x);
  q.e1[1] = tessAt(t.n[1], t.k0, x + 1);
  q.e0[2] = tessAt(t.n[2], t.k1, y);
  q.e1[2] = tessAt(t.n[2], t.k1, y + 1);
  q.e0[3] = tessAt(t.n[3], t.k0, x + 1);
  q.e1[3] = tessAt(t.n[3], t.k0, x);
  q.e0[0] = tessAt(t.n[0], t.k1, y + 1);
  q.e1[0] = tessAt(t.n[0], t.k1, y);
  bool touches[4];
  touches[0] = x == 0;
  touches[1] = y == 0;
  touches[2] = x == t.k0 - 1;
  touches[3] = y == t.k1 - 1;
  for (int o = 0; o < 4; ++o) {
    int k = (o + 1) % 4;
    int steps = tessEdgeSegments(q, k) + tessRingSegments(q, k);
    if (!touches[k] || steps == 0) continue;
    q.has[k] = true;
    q.vEdge[k] = q.vertices;
    q.vertices += tessEdgeSegments(q, k) + 1;
    q.tStrip[k] = q.triangles;
    q.triangles += steps;
  }
  return q;
}

LB_TESS_FN int tessPieces(TessPatch t) {
  return t.k0 * t.k1;
}

LB_TESS_FN TessFrac tessFrac(int un, int ud, int vn, int vd) {
  TessFrac f;
  f.un = un;
  f.ud = ud;
  f.vn = vn;
  f.vd = vd;
  return f;
}

LB_TESS_FN TessFrac tessVertex(TessPatch t, TessPiece q, int i) {
  if (t.allOne) return tessFrac(i == 1 || i == 2 ? 1 : 0, 1, i >= 2 ? 1 : 0, 1);
  int block = q.w * (q.b1 - q.b0 + 1);
  if (i < block) return tessFrac(q.a0 + i % q.w, t.m0, q.b0 + i / q.w, t.m1);
  int k = -1;  // the strip whose edge row starts last at or before i
  for (int e = 0; e < 4; ++e)
    if (q.has[e] && i >= q.vEdge[e] && (k < 0 || q.vEdge[e] > q.vEdge[k])) k = e;
  int j = i - q.vEdge[k];
  int p = q.e1[k] >= q.e0[k] ? q.e0[k] + j : q.e0[k] - j;
  if (k == 0) return tessFrac(0, 1, p, t.n[0]);
  if (k == 1) return tessFrac(p, t.n[1], 0, 1);
  if (k == 2) return tessFrac(1, 1, p, t.n[2]);
  return tessFrac(p, t.n[3], 1, 1);
}

// Point j of strip k's ring row, walked as the strip walks.
LB_TESS_FN int tessRingVertex(TessPiece q, int k, int j) {
  int a = k == 1 ? q.a0 + j : (k == 3 ? q.a1 - j : (k == 2 ? q.a1 : q.a0));
  int b = k == 2 ? q.b0 + j : (k == 0 ? q.b1 - j : (k == 1 ? q.b0 : q.b1));
  return (b - q.b0) * q.w + (a - q.a0);
}

LB_TESS_FN TessTri tessTri(int a, int b, int c) {
  TessTri r;
  r.a = a;
  r.b = b;
  r.c = c;
  return r;
}

LB_TESS_FN TessTri tessTriangle(TessPatch t, TessPiece q, int tri) {
  if (t.allOne) return tri == 0 ? tessTri(0, 1, 2) : tessTri(0, 2, 3);
  if (tri < 2 * q.cells) {
    // The (0,0)-(1,1) diagonal in every cell, as every grid footprint of the renderer.
    int c = tri / 2, wc = q.a1 - q.a0;
    int v00 = (c / wc) * q.w + c % wc;
    return tri % 2 == 0 ? tessTri(v00, v00 + 1, v00 + q.w + 1) : tessTri(v00, v00 + q.w + 1, v00 + q.w);
  }
  int k = 1;
  for (int o = 0; o < 4; ++o) {
    int e = (o + 1) % 4;
    if (q.has[e] && tri >= q.tStrip[e]) k = e;
  }
  int s = tri - q.tStrip[k];
  int steps = int(LB_TESS_STEPS(tessEdgeSegments(q, k), tessRingSegments(q, k)));
  int i = LB_TESS_BITCOUNT(steps & ((1 << s) - 1)), j = s - i;
  int edge = q.vEdge[k] + i;
  if (((steps >> s) & 1) != 0) return tessTri(edge, edge + 1, tessRingVertex(q, k, j));
  return tessTri(edge, tessRingVertex(q, k, j + 1), tessRingVertex(q, k, j));
}

#ifdef __cplusplus
}  // namespace tesspiece
}  // namespace lb
#endif
#undef LB_TESS_FN

#endif
