// impulse/shapes/detail/quickhull.hpp — the quickhull construction behind convex_hull.
//
// Quickhull (Barber, Dobkin & Huhdanpaa, "The Quickhull Algorithm for Convex
// Hulls", ACM Trans. Math. Software 22(4), 1996), made robust after Dirk
// Gregorius, "Implementing Quickhull" (GDC 2014):
//
// - Fat planes. A point is outside a face only when it is more than a
//   tolerance above the face's plane; points within it are on the hull and
//   are dropped, which is how duplicates and nearly coplanar points merge.
//   Points closer together than the tolerance are welded into one first.
// - Faces are polygons in a half-edge mesh. New faces absorb neighbours
//   across edges that are concave or nearly coplanar (wants_merge), so nearly
//   coplanar triangles become one polygon and nearly concave edges go as they
//   appear instead of accumulating until a later horizon is no longer a
//   simple loop. Unlike the talk, a merge must leave a polygon that is flat
//   and convex within the tolerance, taking in more coplanar faces if that
//   is what it takes (merge_region); the reasons are given at each test.
// - Merging can leave a vertex on only two faces, a face with two edges or an
//   edge hanging into a face; each is repaired on the spot (fix_topology), as
//   Jolt Physics' ConvexHullBuilder (J. Rouwe), which follows the same talk,
//   does.
// - A face is visible from a new point when the point is above its plane at
//   all. If rounding still makes the visible faces something other than a
//   disc, or the cone from the point folds inwards at a horizon vertex, more
//   faces are taken as visible. Vertices that leave the hull, and points
//   dropped while within the tolerance outside, are offered back later, so a
//   point that rounding cut off is added again if it really lies outside.
// - Each face's plane is finally moved out to the hull's farthest vertex
//   along its normal, so that every plane supports the hull.
//
// Everything here is double, whatever the scalar of the hull, and the caller
// (convex_hull.hpp) hands in coordinates translated to the center of the
// points and scaled by a power of two into [-1, 1]. For float points the
// construction runs with the tolerance of double arithmetic and merges with
// the float tolerance at the end (see build()).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "../../math/vec3.hpp"

namespace impulse::detail {

/// An edge of the built hull: hull vertex indices a, b; the faces on which
/// the boundary runs a -> b and b -> a.
struct quickhull_edge {
  std::uint32_t a;
  std::uint32_t b;
  std::uint32_t face_ab;
  std::uint32_t face_ba;
};

/// The hull in flat arrays, as convex_hull stores it.
struct quickhull_output {
  std::vector<std::uint32_t> vertex_points;  ///< input index of each hull vertex, ascending
  std::vector<std::uint32_t> face_offsets;   ///< face f is face_vertices[face_offsets[f], face_offsets[f + 1])
  std::vector<std::uint32_t> face_vertices;  ///< hull vertex indices, counter-clockwise from outside
  std::vector<vec3<double>> normals;         ///< unit outward normal of each face
  std::vector<std::uint32_t> supports;       ///< hull vertex farthest along each face's normal
  std::vector<quickhull_edge> edges;         ///< each edge once
};

enum class quickhull_status : std::uint8_t { ok, coincident, collinear, coplanar };

// A template only so that a translation unit that never builds a hull does
// not pay for checking this class: its members are compiled on first use.
template <class Unused = void>
class basic_quickhull {
 public:
  /// Builds the hull of `points` (coordinates of order 1). Fat planes of
  /// half-thickness `tolerance` decide which points are outside; faces are
  /// merged, and the input is judged degenerate, with `merge_tolerance`
  /// (at least `tolerance`). Returns why not when the points do not span a
  /// volume thicker than `merge_tolerance`; `out` is filled only on success.
  ///
  /// The two differ when the points carry less precision than the double
  /// arithmetic here (a float hull): the construction then runs with the
  /// tolerance of that arithmetic, which resolves features a few float
  /// roundings across exactly, and the faces it finds are merged with the
  /// points' own tolerance once it is done. Merging as it goes, at the
  /// points' tolerance, would decide in tolerance-sized clusters of points
  /// which side of a face tiny as the cluster a point is on, and a plane
  /// that small tilts by a large angle for an error of one tolerance.
  quickhull_status build(std::span<const vec3<double>> points, double tolerance, double merge_tolerance,
                         quickhull_output& out) {
    points_ = points;
    tolerance_ = tolerance;
    const std::size_t n = points.size();
    next_conflict_.assign(n, none);
    point_mark_.assign(n, 0);
    pool_mark_.assign(n, 0);
    horizon_from_.assign(n, none);
    on_hull_.assign(n, 0);
    removed_before_.assign(n, 0);
    is_near_.assign(n, 0);
    near_.clear();
    edges_.clear();
    faces_.clear();
    pending_.clear();
    stamp_ = 0;
    always_strict_ = false;

    weld(merge_tolerance);
    const quickhull_status status = initial_simplex(merge_tolerance);
    if (status != quickhull_status::ok) return status;

    // Each step adds the farthest outside point of some face. A point leaves
    // the hull again only if rounding cut it off and it was offered back,
    // which a consistent build never needs; the budget bounds that loop
    // should it ever cycle. When no face has an outside point left, the
    // points dropped as within the tolerance are offered to the finished
    // faces (sweep_near), and any that a later face left outside start the
    // loop again; twice at most, as each round finds fewer.
    std::size_t budget = 4 * n + 64;
    for (int round = 0;; ++round) {
      while (!pending_.empty() && budget > 0) {
        const std::uint32_t f = pending_.back();
        pending_.pop_back();
        if (!faces_[f].alive || faces_[f].furthest == none) continue;
        --budget;
        const std::uint32_t eye = faces_[f].furthest;
        if (!add_point(eye, f)) {
          // The faces it sees could not be made a disc: leave the point
          // out rather than break the mesh.
          drop_conflict(f, eye);
          if (faces_[f].furthest != none) pending_.push_back(f);
        }
      }
      if (round == 2 || !sweep_near()) break;
    }
    if (merge_tolerance > tolerance_) {
      // The faces found are exact for points this coarse, needles included:
      // every polygon merged from them must be convex in the strict sense.
      tolerance_ = merge_tolerance;
      always_strict_ = true;
      ++stamp_;
      touched_.clear();
      orphans_.clear();
      worklist_.clear();
      for (std::uint32_t f = 0; f < faces_.size(); ++f) {
        if (faces_[f].alive) worklist_.push_back(f);
      }
      while (!worklist_.empty()) {
        const std::uint32_t f = worklist_.back();
        worklist_.pop_back();
        if (faces_[f].alive) process(f);
      }
    }
    // Merging collapses a hull thinner than a few tolerances to two faces
    // back to back, or to nothing: that input was flat after all.
    std::size_t alive = 0;
    for (const face_record& face : faces_) alive += face.alive ? 1 : 0;
    if (alive < 4) return quickhull_status::coplanar;
    extract(out);
    return quickhull_status::ok;
  }

 private:
  static constexpr std::uint32_t none = 0xffffffffu;

  struct half_edge {
    std::uint32_t origin;  // point index
    std::uint32_t twin;
    std::uint32_t next;    // counter-clockwise around the face, seen from outside
    std::uint32_t prev;
    std::uint32_t face;
  };

  struct face_record {
    std::uint32_t edge = none;  // any half-edge of its boundary
    vec3<double> normal{};      // unit outward; zero for a face with no area
    vec3<double> centroid{};    // area-weighted: the point the plane goes through
    double area2 = 0;           // twice the area
    std::uint32_t conflicts = none;  // head of the list of points above it
    std::uint32_t furthest = none;
    double furthest_distance = 0;
    std::uint32_t visible = 0;  // == stamp_: visible from the point being added
    std::uint32_t touched = 0;  // == stamp_: created or changed while adding it
    bool alive = true;
  };

  // ---- geometry -------------------------------------------------------------

  const vec3<double>& point(std::uint32_t p) const noexcept { return points_[p]; }
  std::uint32_t dest(std::uint32_t h) const noexcept { return edges_[edges_[h].next].origin; }
  std::uint32_t neighbour(std::uint32_t h) const noexcept { return edges_[edges_[h].twin].face; }

  double distance(std::uint32_t f, const vec3<double>& p) const noexcept {
    return dot(faces_[f].normal, p - faces_[f].centroid);
  }

  std::size_t edge_count(std::uint32_t f) const noexcept {
    std::size_t count = 0;
    std::uint32_t h = faces_[f].edge;
    do {
      ++count;
      h = edges_[h].next;
    } while (h != faces_[f].edge && count <= edges_.size());
    return count;
  }

  /// Twice the area vector of triangle (a, b, c): the cross product of its
  /// two shorter edges, the most accurate of the three (Catto, "The
  /// troublesome triangle", 2014). Of a needle two edges are long and nearly
  /// parallel, and their cross product is all cancellation.
  static vec3<double> area_vector(const vec3<double>& a, const vec3<double>& b, const vec3<double>& c) noexcept {
    const vec3<double> e0 = b - a, e1 = c - b, e2 = a - c;
    const double l0 = length_squared(e0), l1 = length_squared(e1), l2 = length_squared(e2);
    if (l0 >= l1 && l0 >= l2) return cross(e1, e2);
    return l1 >= l2 ? cross(e2, e0) : cross(e0, e1);
  }

  /// Centroid and normal of a face: the sums over a fan of triangles from
  /// its first vertex of their area vectors and of their area-weighted
  /// centroids. For a nearly planar polygon that is its best plane (Newell's
  /// normal, computed without the cancellation of needle-shaped fans), and a
  /// large face keeps its plane when a sliver joins it, which the mean of
  /// the vertices would shift by as much as a vertex.
  void update_plane(std::uint32_t f) noexcept {
    face_record& face = faces_[f];
    const vec3<double>& first = point(edges_[face.edge].origin);
    vec3<double> sum = first, n{}, weighted{};
    double weight = 0;
    std::size_t count = 1;
    for (std::uint32_t h = edges_[face.edge].next; h != face.edge; h = edges_[h].next) {
      const vec3<double>& b = point(edges_[h].origin);
      sum += b;
      ++count;
      if (edges_[h].next == face.edge) continue;
      const vec3<double>& c = point(dest(h));
      const vec3<double> a = area_vector(first, b, c);
      const double area = length(a);
      n += a;
      weighted += (first + b + c) * area;
      weight += area;
    }
    const double len = length(n);
    face.area2 = len;
    face.normal = len > 0 ? n / len : vec3<double>{};
    // A face of no area has no weighted centroid: the mean of its vertices.
    face.centroid = weight > 0 ? weighted / (3 * weight) : sum / double(count);
  }

  /// Thinner than the tolerance across its longest edge: its normal is
  /// mostly rounding, so it cannot take part in convexity tests.
  bool is_degenerate(std::uint32_t f) const noexcept {
    const std::uint32_t h = longest_edge(f);
    return faces_[f].area2 <= tolerance_ * length(point(dest(h)) - point(edges_[h].origin));
  }

  std::uint32_t longest_edge(std::uint32_t f) const noexcept {
    std::uint32_t best = faces_[f].edge;
    double best_length = -1;
    std::uint32_t h = faces_[f].edge;
    do {
      const double l = length_squared(point(dest(h)) - point(edges_[h].origin));
      if (l > best_length) {
        best_length = l;
        best = h;
      }
      h = edges_[h].next;
    } while (h != faces_[f].edge);
    return best;
  }

  /// Whether the faces on either side of f's half-edge h ought to be one,
  /// before asking if their union is a convex polygon (see process()).
  ///
  /// The edge is judged against the plane of the larger face, r, with the
  /// smaller one, o: a small face's normal carries rounding of order (point
  /// error)/(its size), which its plane multiplies by the distance to the
  /// other face's centroid, so Gregorius' test of each centroid against the
  /// other plane calls a tiny face beside a large one concave or convex at
  /// random. Heights are measured from the shared edge, since a merged face's
  /// vertices lie up to the tolerance off its plane.
  /// - A vertex of o more than the tolerance above r: concave; yes.
  /// - o's centroid more than the tolerance below r: convex; no.
  /// - Otherwise nearly coplanar: yes if the union is flat within the
  ///   tolerance. Without this a fan of slightly tilted faces (around a point
  ///   a few tolerances above the middle of a large face) merges a pair at a
  ///   time into a face no plane fits, and the point is lost.
  /// Faces back to back (a sliver of a hull) never: their union has no plane.
  bool wants_merge(std::uint32_t f, std::uint32_t h) const noexcept {
    const std::uint32_t g = neighbour(h);
    if (g == f || !(dot(faces_[f].normal, faces_[g].normal) > 0)) return false;
    const std::uint32_t r = faces_[f].area2 >= faces_[g].area2 ? f : g;
    const std::uint32_t o = r == f ? g : f;
    const std::uint32_t x = edges_[h].origin, y = dest(h);
    const double base = 0.5 * (distance(r, point(x)) + distance(r, point(y)));
    double highest = -std::numeric_limits<double>::max();
    std::uint32_t e = faces_[o].edge;
    do {
      const std::uint32_t v = edges_[e].origin;
      if (v != x && v != y) {
        const double d = distance(r, point(v)) - base;
        highest = d > highest ? d : highest;
      }
      e = edges_[e].next;
    } while (e != faces_[o].edge);
    if (highest > tolerance_) return true;
    if (distance(r, faces_[o].centroid) - base < -tolerance_) return false;
    return union_is_flat(f, h);
  }

  /// True when a polygon of normal n turns the wrong way at `corner` by more
  /// than the tolerance. Loosely: the corner lies that far inside the chord
  /// from `before` to `after`. Strictly: the next vertex lies that far
  /// outside the line of the edge into the corner, or the previous one
  /// outside the line of the edge out of it. The strict test is for unions
  /// of faces at a steep angle: a face a few tolerances wide can join a
  /// large one almost folded back, with a corner within the tolerance of
  /// the chord but an edge that points backwards, a side plane that would
  /// clip the whole face away. Between nearly parallel faces the loose test
  /// lets a point a few tolerances from a vertex (a near duplicate) join
  /// the face beside it; the strict one would judge the direction of the
  /// tiny edge between them, which is rounding, and leave a needle-shaped
  /// face whose plane that rounding tilts.
  bool is_reflex(const vec3<double>& before, const vec3<double>& corner, const vec3<double>& after,
                 const vec3<double>& n, bool strict) const noexcept {
    if (!strict) {
      const vec3<double> outward = cross(after - before, n);
      return dot(outward, corner - before) < -tolerance_ * length(outward);
    }
    const vec3<double> out_in = cross(corner - before, n), out_out = cross(after - corner, n);
    return dot(out_in, after - corner) > tolerance_ * length(out_in) ||
           dot(out_out, before - corner) > tolerance_ * length(out_out);
  }

  /// cos 8°: faces whose normals differ by more are distinct facets of any
  /// hull worth colliding with, and a polygon made of them must be convex
  /// in the strict sense of is_reflex.
  static constexpr double steep_cosine = 0.99;

  /// The plane update_plane would give the union of f and the face across
  /// h: the sum of their area vectors, through their area-weighted centroid.
  void union_plane(std::uint32_t f, std::uint32_t h, vec3<double>& normal, vec3<double>& centroid) const noexcept {
    const face_record& a = faces_[f];
    const face_record& b = faces_[neighbour(h)];
    const vec3<double> n = a.normal * a.area2 + b.normal * b.area2;
    const double len = length(n);
    normal = len > 0 ? n / len : vec3<double>{};
    const double weight = a.area2 + b.area2;
    centroid = weight > 0 ? (a.centroid * a.area2 + b.centroid * b.area2) / weight : (a.centroid + b.centroid) * 0.5;
  }

  /// Every vertex of the union of f and the face across h within the
  /// tolerance of the union's plane.
  bool union_is_flat(std::uint32_t f, std::uint32_t h) const noexcept {
    vec3<double> n, c;
    union_plane(f, h, n, c);
    if (length_squared(n) == 0) return false;
    for (const std::uint32_t k : {f, neighbour(h)}) {
      std::uint32_t e = faces_[k].edge;
      do {
        if (std::abs(dot(n, point(edges_[e].origin) - c)) > tolerance_) return false;
        e = edges_[e].next;
      } while (e != faces_[k].edge);
    }
    return true;
  }

  /// No reflex corner where the boundaries of f and the face across h join
  /// (elsewhere each was convex already).
  bool union_is_convex(std::uint32_t f, std::uint32_t h) const noexcept {
    vec3<double> n, c;
    union_plane(f, h, n, c);
    const std::uint32_t t = edges_[h].twin;
    const bool strict = always_strict_ || dot(faces_[f].normal, faces_[neighbour(h)].normal) < steep_cosine;
    return !is_reflex(point(edges_[edges_[h].prev].origin), point(edges_[h].origin), point(dest(edges_[t].next)), n, strict) &&
           !is_reflex(point(edges_[edges_[t].prev].origin), point(dest(h)), point(dest(edges_[h].next)), n, strict);
  }

  // ---- mesh surgery ---------------------------------------------------------

  void link(std::uint32_t a, std::uint32_t b) noexcept {
    edges_[a].next = b;
    edges_[b].prev = a;
  }
  void link_twins(std::uint32_t a, std::uint32_t b) noexcept {
    edges_[a].twin = b;
    edges_[b].twin = a;
  }

  std::uint32_t new_face(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const auto f = static_cast<std::uint32_t>(faces_.size());
    const auto e = static_cast<std::uint32_t>(edges_.size());
    faces_.push_back({});
    edges_.push_back({a, none, e + 1, e + 2, f});
    edges_.push_back({b, none, e + 2, e, f});
    edges_.push_back({c, none, e, e + 1, f});
    faces_[f].edge = e;
    update_plane(f);
    return f;
  }

  void touch(std::uint32_t f) {
    if (faces_[f].touched != stamp_) {
      faces_[f].touched = stamp_;
      touched_.push_back(f);
    }
  }

  /// Moves a face's conflict list to the orphans, to be assigned again;
  /// except the point being added, which is on the hull now.
  void release_conflicts(std::uint32_t f) {
    for (std::uint32_t p = faces_[f].conflicts; p != none;) {
      const std::uint32_t next = next_conflict_[p];
      if (!on_hull_[p]) orphans_.push_back(p);
      p = next;
    }
    faces_[f].conflicts = none;
    faces_[f].furthest = none;
  }

  void kill_face(std::uint32_t f) {
    faces_[f].alive = false;
    release_conflicts(f);
  }

  /// A vertex no face uses any more is offered back as a candidate point,
  /// in case rounding, not geometry, took it off the hull; but only the first
  /// time. A point that merging removes again and again (one within about
  /// the tolerance of an edge line, say) would otherwise be added and removed
  /// forever; after its second removal it waits for the final sweep.
  void remove_vertex(std::uint32_t p) {
    on_hull_[p] = 0;
    if (!removed_before_[p]) orphans_.push_back(p);
    else note_near(p);
    removed_before_[p] = 1;
  }

  /// f absorbs the face across its half-edge h; the edge between them goes.
  void merge(std::uint32_t f, std::uint32_t h) {
    const std::uint32_t t = edges_[h].twin;
    const std::uint32_t g = edges_[t].face;
    const std::uint32_t ph = edges_[h].prev, nh = edges_[h].next;
    const std::uint32_t pt = edges_[t].prev, nt = edges_[t].next;
    for (std::uint32_t e = nt; e != t; e = edges_[e].next) edges_[e].face = f;
    link(ph, nt);
    link(pt, nh);
    if (faces_[f].edge == h) faces_[f].edge = nh;
    kill_face(g);
    update_plane(f);
    touch(f);
  }

  /// A face left with two edges is a sliver between its two neighbours: they
  /// become each other's neighbours and the face goes.
  void remove_two_edge_face(std::uint32_t f) {
    const std::uint32_t e1 = faces_[f].edge, e2 = edges_[e1].next;
    const std::uint32_t b1 = edges_[e1].twin, b2 = edges_[e2].twin;
    link_twins(b1, b2);
    kill_face(f);
    for (const std::uint32_t g : {edges_[b1].face, edges_[b2].face}) {
      touch(g);
      worklist_.push_back(g);
    }
  }

  /// Repairs what merging leaves behind on f's boundary, until none is left:
  /// an edge that runs out and straight back (its far vertex is gone), and a
  /// vertex shared with only one other face, which is on the line where the
  /// two meet and is removed from both. Returns false if f itself went.
  bool fix_topology(std::uint32_t f) {
    bool changed = false;
    for (;;) {
      if (edge_count(f) < 3) {
        remove_two_edge_face(f);
        return false;
      }
      bool repaired = false;
      const std::uint32_t start = faces_[f].edge;
      std::uint32_t h = start;
      do {
        const std::uint32_t n = edges_[h].next;
        const std::uint32_t th = edges_[h].twin, tn = edges_[n].twin;
        if (th == n) {
          // h = x -> w and n = w -> x, both on f: w hangs into the face.
          const std::uint32_t p = edges_[h].prev, q = edges_[n].next;
          link(p, q);
          faces_[f].edge = p;
          remove_vertex(edges_[n].origin);
          repaired = true;
        } else if (edges_[th].face == edges_[tn].face && edges_[tn].next == th) {
          // h = w -> x and n = x -> z on f; tn = z -> x and th = x -> w on a:
          // x lies on f and a only, and goes: h becomes w -> z, tn z -> w.
          // Within the tolerance of both planes, x moves the surface by about
          // that much. (Where the faces are back to back, as the two sides of
          // a hull a few tolerances thin, x may be far out along the rim; it
          // is offered back as a candidate like any vertex that leaves the
          // hull, and if it lies outside it returns.) But not if either face
          // would turn over without x, as a face whose corner x was, with the
          // rest of it a sliver, would: then x stays, on two faces.
          const std::uint32_t a = edges_[th].face;
          const vec3<double> cut = area_vector(point(edges_[h].origin), point(edges_[n].origin), point(dest(n)));
          if (!(dot(faces_[f].normal * faces_[f].area2 - cut, faces_[f].normal) > 0) ||
              !(dot(faces_[a].normal * faces_[a].area2 + cut, faces_[a].normal) > 0)) {
            h = n;
            continue;
          }
          link(h, edges_[n].next);
          if (faces_[f].edge == n) faces_[f].edge = h;
          link(tn, edges_[th].next);
          if (faces_[a].edge == th) faces_[a].edge = tn;
          link_twins(h, tn);
          remove_vertex(edges_[n].origin);
          if (edge_count(a) < 3) {
            remove_two_edge_face(a);
          } else {
            update_plane(a);
            touch(a);
            worklist_.push_back(a);
          }
          repaired = true;
        }
        if (repaired) break;
        h = n;
      } while (h != start);
      if (!repaired) break;
      changed = true;
    }
    if (changed) {
      update_plane(f);
      touch(f);
    }
    return true;
  }

  /// Merges f with its neighbours until no edge of f wants merging (see
  /// wants_merge) with a union that is a convex polygon, or that can be made
  /// one by taking in more coplanar faces (merge_region). Otherwise the
  /// faces stay apart: a concavity of a few tolerances is better than a
  /// polygon that folds back on itself, whose edges would give the
  /// separating axis test side planes that point the wrong way.
  void process(std::uint32_t f) {
    if (!fix_topology(f)) return;
    // A sliver joins the face across its longest edge, the one whose plane
    // it lies closest to.
    for (std::size_t guard = 0; is_degenerate(f) && guard < 8; ++guard) {
      const std::uint32_t h = longest_edge(f);
      if (neighbour(h) == f) break;
      merge(f, h);
      if (!fix_topology(f)) return;
    }
    for (bool merged = true; merged;) {
      merged = false;
      const std::uint32_t start = faces_[f].edge;
      std::uint32_t h = start;
      do {
        if (wants_merge(f, h)) {
          if (union_is_convex(f, h)) {
            merge(f, h);
            merged = true;
          } else {
            merged = merge_region(f, h);
          }
          if (merged) {
            if (!fix_topology(f)) return;
            break;
          }
        }
        h = edges_[h].next;
      } while (h != start);
    }
  }

  bool in_region(std::uint32_t k) const noexcept {
    for (const std::uint32_t r : region_) {
      if (r == k) return true;
    }
    return false;
  }

  /// Merges f, the face across its half-edge h and as many faces as it takes
  /// around the reflex corners of their union, if that makes one convex
  /// polygon flat within the tolerance, none back to back with f. Three
  /// coplanar triangles around a vertex, or a fan of coplanar triangles from
  /// a corner of a face to points along its far edge, have reflex corners
  /// after any one merge and none after all. Returns whether it merged.
  bool merge_region(std::uint32_t f, std::uint32_t h) {
    // A region grows by the faces around one reflex corner at a time; a
    // coplanar patch of a few dozen faces is the most a hull presents.
    constexpr std::size_t max_region = 64;
    region_.assign({f, neighbour(h)});
    bool strict = always_strict_ || dot(faces_[f].normal, faces_[neighbour(h)].normal) < steep_cosine;
    for (;;) {
      vec3<double> n{};
      for (const std::uint32_t k : region_) n += faces_[k].normal * faces_[k].area2;
      const double len = length(n);
      if (!(len > 0)) return false;
      n = n / len;
      boundary_.clear();
      for (const std::uint32_t k : region_) {
        std::uint32_t b = faces_[k].edge;
        do {
          if (!in_region(neighbour(b))) boundary_.push_back(b);
          b = edges_[b].next;
        } while (b != faces_[k].edge);
      }
      // Chain the boundary into one loop; note its reflex corners.
      bool simple = boundary_.size() >= 3;
      for (const std::uint32_t b : boundary_) {
        std::uint32_t& slot = horizon_from_[edges_[b].origin];
        if (slot != none) simple = false;
        else slot = b;
      }
      reflex_.clear();
      if (simple) {
        std::size_t walked = 0;
        std::uint32_t b = boundary_[0];
        do {
          const std::uint32_t next = horizon_from_[dest(b)];
          if (next == none) break;
          if (is_reflex(point(edges_[b].origin), point(dest(b)), point(dest(next)), n, strict)) reflex_.push_back(next);
          b = next;
          ++walked;
        } while (b != boundary_[0] && walked <= boundary_.size());
        simple = b == boundary_[0] && walked == boundary_.size();
      }
      for (const std::uint32_t b : boundary_) horizon_from_[edges_[b].origin] = none;
      if (!simple) return false;
      if (reflex_.empty()) break;
      // Take in the faces around each reflex corner (reflex_ holds the
      // boundary edge leaving it).
      const std::size_t before = region_.size();
      for (const std::uint32_t out : reflex_) {
        std::uint32_t e = out;
        do {
          const std::uint32_t k = edges_[e].face;
          if (!in_region(k)) {
            const double cosine = dot(faces_[f].normal, faces_[k].normal);
            if (!(cosine > 0) || region_.size() >= max_region) return false;
            strict = strict || cosine < steep_cosine;
            region_.push_back(k);
          }
          e = edges_[edges_[e].prev].twin;
        } while (e != out);
      }
      if (region_.size() == before) return false;
    }
    // Flat: every vertex within the tolerance of the plane the merged face
    // will have (the summed normal, through the area-weighted centroid).
    vec3<double> n{}, c{};
    double weight = 0;
    for (const std::uint32_t k : region_) {
      n += faces_[k].normal * faces_[k].area2;
      c += faces_[k].centroid * faces_[k].area2;
      weight += faces_[k].area2;
    }
    n = n / length(n);
    c = c / weight;
    for (const std::uint32_t k : region_) {
      std::uint32_t b = faces_[k].edge;
      do {
        if (std::abs(dot(n, point(edges_[b].origin) - c)) > tolerance_) return false;
        b = edges_[b].next;
      } while (b != faces_[k].edge);
    }
    // Merge in an order that keeps each next face adjacent to f.
    for (bool progress = true; progress;) {
      progress = false;
      for (const std::uint32_t k : region_) {
        if (k == f || !faces_[k].alive) continue;
        std::uint32_t b = faces_[f].edge;
        do {
          if (neighbour(b) == k) {
            merge(f, b);
            progress = true;
            break;
          }
          b = edges_[b].next;
        } while (b != faces_[f].edge);
      }
    }
    return true;
  }

  // ---- conflict lists -------------------------------------------------------

  void add_conflict(std::uint32_t f, std::uint32_t p, double d) noexcept {
    face_record& face = faces_[f];
    next_conflict_[p] = face.conflicts;
    face.conflicts = p;
    if (face.furthest == none || d > face.furthest_distance) {
      face.furthest = p;
      face.furthest_distance = d;
    }
  }

  /// Puts p on the conflict list of the candidate face it is farthest above,
  /// if that is more than the tolerance; otherwise p is on or inside the hull.
  /// A point within the tolerance above its best face is dropped but noted
  /// in near_: a face built later beside that one may have it farther out.
  void assign(std::uint32_t p, std::span<const std::uint32_t> candidates) {
    std::uint32_t best = none;
    double best_distance = -std::numeric_limits<double>::max();
    for (const std::uint32_t f : candidates) {
      if (!faces_[f].alive) continue;
      const double d = distance(f, point(p));
      if (d > best_distance) {
        best_distance = d;
        best = f;
      }
    }
    if (best == none) return;
    if (best_distance > tolerance_) add_conflict(best, p, best_distance);
    else if (best_distance > 0) note_near(p);
  }

  void note_near(std::uint32_t p) {
    if (!is_near_[p]) {
      is_near_[p] = 1;
      near_.push_back(p);
    }
  }

  /// Offers the noted points to every face once construction has run out
  /// of outside points (Jolt's ConvexHullBuilder keeps a similar list of
  /// "coplanar" points). True if one was more than the tolerance outside.
  /// Faces in the outer loop: the few points stay in cache while the faces
  /// stream past once.
  bool sweep_near() {
    std::size_t kept = 0;
    for (const std::uint32_t p : near_) {
      if (on_hull_[p]) is_near_[p] = 0;
      else near_[kept++] = p;
    }
    near_.resize(kept);
    if (near_.empty()) return false;
    near_best_.assign(near_.size(), none);
    near_distance_.assign(near_.size(), tolerance_);
    for (std::uint32_t f = 0; f < faces_.size(); ++f) {
      if (!faces_[f].alive) continue;
      for (std::size_t i = 0; i < near_.size(); ++i) {
        const double d = distance(f, point(near_[i]));
        if (d > near_distance_[i]) {
          near_distance_[i] = d;
          near_best_[i] = f;
        }
      }
    }
    bool found = false;
    kept = 0;
    for (std::size_t i = 0; i < near_.size(); ++i) {
      const std::uint32_t p = near_[i];
      if (near_best_[i] == none) {
        near_[kept++] = p;
        continue;
      }
      is_near_[p] = 0;
      add_conflict(near_best_[i], p, near_distance_[i]);
      pending_.push_back(near_best_[i]);
      found = true;
    }
    near_.resize(kept);
    return found;
  }

  void drop_conflict(std::uint32_t f, std::uint32_t p) noexcept {
    std::uint32_t list = faces_[f].conflicts;
    faces_[f].conflicts = none;
    faces_[f].furthest = none;
    while (list != none) {
      const std::uint32_t next = next_conflict_[list];
      if (list != p) add_conflict(f, list, distance(f, point(list)));
      list = next;
    }
  }

  // ---- construction ---------------------------------------------------------

  /// Marks in welded_ every point within `radius` of an earlier point that
  /// is kept: duplicates and near duplicates are one point, so no edge of
  /// the hull is shorter than the tolerance, where its direction, and the
  /// convexity of a polygon at its ends, would be rounding. Points are found
  /// through a hash of a grid of cells `radius` wide (a near duplicate is in
  /// one of the 27 cells around its point); the first of a group is kept,
  /// so the result does not depend on anything but the order of the input.
  void weld(double radius) {
    const std::size_t n = points_.size();
    welded_.assign(n, 0);
    std::size_t buckets = 16;
    while (buckets < 2 * n) buckets *= 2;
    bucket_.assign(buckets, none);
    chain_.assign(n, none);
    const double inverse = 1 / radius;
    const auto cell = [&](const vec3<double>& p, int axis) { return static_cast<std::int64_t>(std::floor(p[axis] * inverse)); };
    const auto slot = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      // Large odd multipliers mix the three cell coordinates (as in Teschner
      // et al., "Optimized Spatial Hashing for Collision Detection", 2003).
      const std::uint64_t h = static_cast<std::uint64_t>(x) * 73856093u ^ static_cast<std::uint64_t>(y) * 19349663u ^
                              static_cast<std::uint64_t>(z) * 83492791u;
      return static_cast<std::size_t>((h ^ (h >> 29)) & (buckets - 1));
    };
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::int64_t x = cell(point(i), 0), y = cell(point(i), 1), z = cell(point(i), 2);
      bool near = false;
      for (std::int64_t dx = -1; dx <= 1 && !near; ++dx) {
        for (std::int64_t dy = -1; dy <= 1 && !near; ++dy) {
          for (std::int64_t dz = -1; dz <= 1 && !near; ++dz) {
            for (std::uint32_t j = bucket_[slot(x + dx, y + dy, z + dz)]; j != none; j = chain_[j]) {
              if (length_squared(point(j) - point(i)) <= radius * radius) {
                near = true;
                break;
              }
            }
          }
        }
      }
      if (near) {
        welded_[i] = 1;
        continue;
      }
      const std::size_t b = slot(x, y, z);
      chain_[i] = bucket_[b];
      bucket_[b] = i;
    }
  }

  /// The first tetrahedron: the widest pair of axis extremes, the point
  /// farthest from their line and the point farthest from their plane. Its
  /// size is also the test of degenerate input, each against `flat`.
  quickhull_status initial_simplex(double flat) {
    const std::size_t n = points_.size();
    std::uint32_t extreme[6] = {0, 0, 0, 0, 0, 0};  // point 0 is never welded away
    for (std::uint32_t i = 0; i < n; ++i) {
      if (welded_[i]) continue;
      for (int axis = 0; axis < 3; ++axis) {
        if (point(i)[axis] < point(extreme[2 * axis])[axis]) extreme[2 * axis] = i;
        if (point(i)[axis] > point(extreme[2 * axis + 1])[axis]) extreme[2 * axis + 1] = i;
      }
    }
    std::uint32_t i0 = extreme[0], i1 = extreme[1];
    double widest = -1;
    for (int a = 0; a < 6; ++a) {
      for (int b = a + 1; b < 6; ++b) {
        const double d = length_squared(point(extreme[b]) - point(extreme[a]));
        if (d > widest) {
          widest = d;
          i0 = extreme[a];
          i1 = extreme[b];
        }
      }
    }
    if (!(std::sqrt(widest) > flat)) return quickhull_status::coincident;

    const vec3<double> p0 = point(i0);
    const vec3<double> axis = normalize(point(i1) - p0);
    std::uint32_t i2 = i0;
    double farthest = -1;
    for (std::uint32_t i = 0; i < n; ++i) {
      if (welded_[i]) continue;
      const double d = length(cross(point(i) - p0, axis));
      if (d > farthest) {
        farthest = d;
        i2 = i;
      }
    }
    if (!(farthest > flat)) return quickhull_status::collinear;

    const vec3<double> normal = normalize(cross(point(i1) - p0, point(i2) - p0));
    std::uint32_t i3 = i0;
    double height = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      if (welded_[i]) continue;
      const double d = dot(normal, point(i) - p0);
      if (std::abs(d) > std::abs(height)) {
        height = d;
        i3 = i;
      }
    }
    if (!(std::abs(height) > flat)) return quickhull_status::coplanar;

    // The base (i0, i1, i2) must face away from i3.
    if (height > 0) {
      const std::uint32_t swap = i1;
      i1 = i2;
      i2 = swap;
    }
    const std::uint32_t faces[4] = {new_face(i0, i1, i2), new_face(i1, i0, i3), new_face(i2, i1, i3),
                                    new_face(i0, i2, i3)};
    for (std::uint32_t h = 0; h < 12; ++h) {
      for (std::uint32_t g = h + 1; g < 12; ++g) {
        if (edges_[h].origin == dest(g) && dest(h) == edges_[g].origin) link_twins(h, g);
      }
    }
    for (const std::uint32_t v : {i0, i1, i2, i3}) on_hull_[v] = 1;
    for (std::uint32_t i = 0; i < n; ++i) {
      if (!on_hull_[i] && !welded_[i]) assign(i, faces);
    }
    for (const std::uint32_t f : faces) {
      if (faces_[f].furthest != none) pending_.push_back(f);
    }
    return quickhull_status::ok;
  }

  void mark_visible(std::uint32_t f) {
    faces_[f].visible = stamp_;
    visible_.push_back(f);
  }

  /// Orders the boundary of the visible faces into horizon_. False unless it
  /// is one simple loop, as it is when the visible faces form a disc.
  bool find_horizon() {
    boundary_.clear();
    for (const std::uint32_t f : visible_) {
      std::uint32_t h = faces_[f].edge;
      do {
        if (faces_[neighbour(h)].visible != stamp_) boundary_.push_back(h);
        h = edges_[h].next;
      } while (h != faces_[f].edge);
    }
    bool simple = boundary_.size() >= 3;
    for (const std::uint32_t h : boundary_) {
      std::uint32_t& slot = horizon_from_[edges_[h].origin];
      if (slot != none) simple = false;  // two loops touch at this vertex
      else slot = h;
    }
    horizon_.clear();
    if (simple) {
      std::uint32_t h = boundary_[0];
      for (std::size_t i = 0; i < boundary_.size(); ++i) {
        if (h == none || (i > 0 && h == boundary_[0])) break;  // open, or more than one loop
        horizon_.push_back(h);
        h = horizon_from_[dest(h)];
      }
      simple = h == boundary_[0] && horizon_.size() == boundary_.size();
    }
    for (const std::uint32_t h : boundary_) horizon_from_[edges_[h].origin] = none;
    return simple;
  }

  /// Makes the visible faces a disc when rounding did not: invisible faces
  /// enclosed by visible ones, and the faces around a vertex where two
  /// visible regions touch, become visible. Rare; so it is plain, not fast.
  bool repair_visible_set(const vec3<double>& eye) {
    for (int attempt = 0; attempt < 8; ++attempt) {
      bool grew = false;
      // Invisible faces fall into connected groups; all but the one that
      // holds the face the eye is farthest below are enclosed.
      std::vector<std::uint32_t> group(faces_.size(), none);
      std::uint32_t groups = 0, keep = none;
      double lowest = std::numeric_limits<double>::max();
      for (std::uint32_t f = 0; f < faces_.size(); ++f) {
        if (!faces_[f].alive || faces_[f].visible == stamp_ || group[f] != none) continue;
        stack_.assign(1, f);
        group[f] = groups;
        while (!stack_.empty()) {
          const std::uint32_t g = stack_.back();
          stack_.pop_back();
          const double d = distance(g, eye);
          if (d < lowest) {
            lowest = d;
            keep = groups;
          }
          std::uint32_t h = faces_[g].edge;
          do {
            const std::uint32_t k = neighbour(h);
            if (faces_[k].visible != stamp_ && group[k] == none) {
              group[k] = groups;
              stack_.push_back(k);
            }
            h = edges_[h].next;
          } while (h != faces_[g].edge);
        }
        ++groups;
      }
      if (groups == 0) return false;
      for (std::uint32_t f = 0; f < faces_.size(); ++f) {
        if (group[f] != none && group[f] != keep) {
          mark_visible(f);
          grew = true;
        }
      }
      if (!grew) {
        // Pinched vertices: a vertex that two boundary edges leave.
        for (const std::uint32_t h : boundary_) {
          std::uint32_t& slot = horizon_from_[edges_[h].origin];
          if (slot == none) {
            slot = h;
            continue;
          }
          grew = mark_faces_around(h) || grew;
        }
        for (const std::uint32_t h : boundary_) horizon_from_[edges_[h].origin] = none;
      }
      if (!grew) return false;
      if (find_horizon()) return true;
    }
    return false;
  }

  /// True when the cone from the eye folds inwards at the horizon vertex v
  /// between horizon vertices a and b: the far corner of one of its two
  /// triangles is more than the tolerance above the other's plane, judged
  /// against the larger triangle's plane (the better determined one).
  bool cone_folds(const vec3<double>& a, const vec3<double>& v, const vec3<double>& b,
                  const vec3<double>& eye) const noexcept {
    const vec3<double> n1 = cross(v - a, eye - a), n2 = cross(b - v, eye - v);
    const double l1 = length(n1), l2 = length(n2);
    if (l1 >= l2) return l1 > 0 && dot(n1, b - v) > tolerance_ * l1;
    return dot(n2, a - v) > tolerance_ * l2;
  }

  /// Marks the faces around every horizon vertex where the cone folds as
  /// visible, if the eye is within the tolerance of seeing each of them
  /// (otherwise the vertex is a true corner the eye sees past, and cutting
  /// it off would only move the fold); false if there was none.
  bool widen_at_folds(const vec3<double>& eye) {
    bool grew = false;
    const std::size_t k = horizon_.size();
    for (std::size_t i = 0; i < k; ++i) {
      const std::uint32_t h = horizon_[i], before = horizon_[(i + k - 1) % k];
      if (!cone_folds(point(edges_[before].origin), point(edges_[h].origin), point(dest(h)), eye)) continue;
      bool nearly_visible = true;
      std::uint32_t e = h;
      do {
        nearly_visible = nearly_visible && distance(edges_[e].face, eye) >= -tolerance_;
        e = edges_[edges_[e].prev].twin;
      } while (e != h && nearly_visible);
      if (!nearly_visible) continue;
      grew = mark_faces_around(h) || grew;
    }
    return grew;
  }

  /// Marks every face around the origin of edge h visible; true if any was
  /// not already.
  bool mark_faces_around(std::uint32_t h) {
    bool grew = false;
    std::uint32_t e = h;
    do {
      if (faces_[edges_[e].face].visible != stamp_) {
        mark_visible(edges_[e].face);
        grew = true;
      }
      e = edges_[edges_[e].prev].twin;
    } while (e != h);
    return grew;
  }

  /// Adds point `eye`, which is more than the tolerance above face f0.
  bool add_point(std::uint32_t eye, std::uint32_t f0) {
    ++stamp_;
    const vec3<double> e = point(eye);

    // 1. The faces the eye sees, flooded from f0 across edges.
    visible_.clear();
    stack_.clear();
    mark_visible(f0);
    stack_.push_back(f0);
    while (!stack_.empty()) {
      const std::uint32_t f = stack_.back();
      stack_.pop_back();
      std::uint32_t h = faces_[f].edge;
      do {
        const std::uint32_t g = neighbour(h);
        if (faces_[g].visible != stamp_ && distance(g, e) > 0) {
          mark_visible(g);
          stack_.push_back(g);
        }
        h = edges_[h].next;
      } while (h != faces_[f].edge);
    }

    // 2. Their boundary, the horizon, as one loop; and where the cone from
    //    the eye would fold inwards at a horizon vertex, the faces around it
    //    are taken as visible too. In exact arithmetic the cone over the
    //    horizon of a convex hull is convex; a fold means the vertex is
    //    within rounding of the eye's view and is better cut off (it comes
    //    back as a candidate) than kept under a concave edge.
    if (!find_horizon() && !repair_visible_set(e)) return false;
    for (int round = 0; round < 8 && widen_at_folds(e); ++round) {
      if (!find_horizon() && !repair_visible_set(e)) return false;
    }

    // 3. The visible faces go. Their outside points become orphans, and so do
    //    their vertices that are not on the horizon: in exact arithmetic they
    //    are now inside; if rounding says otherwise they come back.
    orphans_.clear();
    touched_.clear();
    worklist_.clear();
    cone_.clear();
    on_hull_[eye] = 1;
    for (const std::uint32_t h : horizon_) point_mark_[edges_[h].origin] = stamp_;
    for (const std::uint32_t f : visible_) {
      kill_face(f);
      std::uint32_t h = faces_[f].edge;
      do {
        const std::uint32_t v = edges_[h].origin;
        if (point_mark_[v] != stamp_) {
          point_mark_[v] = stamp_;
          remove_vertex(v);
        }
        h = edges_[h].next;
      } while (h != faces_[f].edge);
    }

    // 4. A cone of triangles from the horizon to the eye.
    for (const std::uint32_t h : horizon_) {
      const std::uint32_t a = edges_[h].origin, b = dest(h), t = edges_[h].twin;
      const std::uint32_t f = new_face(a, b, eye);
      link_twins(faces_[f].edge, t);
      cone_.push_back(f);
    }
    for (std::size_t i = 0; i < cone_.size(); ++i) {
      const std::uint32_t f = cone_[i], g = cone_[(i + 1) % cone_.size()];
      link_twins(faces_[f].edge + 1, faces_[g].edge + 2);  // b -> eye against eye -> b
    }

    // 5. Merge until every edge of the new faces is clearly convex.
    for (const std::uint32_t f : cone_) {
      touch(f);
      worklist_.push_back(f);
    }
    while (!worklist_.empty()) {
      const std::uint32_t f = worklist_.back();
      worklist_.pop_back();
      if (faces_[f].alive) process(f);
    }

    // 6. Every face that changed gives up its outside points; they and the
    //    orphans go to the changed face they are farthest above, if any.
    for (const std::uint32_t f : touched_) {
      if (faces_[f].alive) release_conflicts(f);
    }
    for (const std::uint32_t p : orphans_) {
      if (on_hull_[p] || pool_mark_[p] == stamp_) continue;
      pool_mark_[p] = stamp_;
      assign(p, touched_);
    }
    for (const std::uint32_t f : touched_) {
      if (faces_[f].alive && faces_[f].furthest != none) pending_.push_back(f);
    }
    return true;
  }

  void extract(quickhull_output& out) {
    std::vector<std::uint32_t> vertex_of(points_.size(), none);
    std::vector<std::uint32_t> face_of(faces_.size(), none);
    out = {};
    std::uint32_t face_count = 0;
    for (std::uint32_t f = 0; f < faces_.size(); ++f) {
      if (!faces_[f].alive) continue;
      face_of[f] = face_count++;
      std::uint32_t h = faces_[f].edge;
      do {
        vertex_of[edges_[h].origin] = 0;
        h = edges_[h].next;
      } while (h != faces_[f].edge);
    }
    for (std::uint32_t p = 0; p < points_.size(); ++p) {
      if (vertex_of[p] == none) continue;
      vertex_of[p] = static_cast<std::uint32_t>(out.vertex_points.size());
      out.vertex_points.push_back(p);
    }
    // One half-edge leaving each vertex, to walk its neighbours.
    std::vector<std::uint32_t> leaving(points_.size(), none);
    for (std::uint32_t f = 0; f < faces_.size(); ++f) {
      if (!faces_[f].alive) continue;
      std::uint32_t h = faces_[f].edge;
      do {
        leaving[edges_[h].origin] = h;
        h = edges_[h].next;
      } while (h != faces_[f].edge);
    }
    // 2^26 multiply-adds: a few milliseconds, the order of building a hull
    // of thousands of points.
    const bool scan = double(out.vertex_points.size()) * double(face_count) <= 67108864.0;
    out.face_offsets.push_back(0);
    for (std::uint32_t f = 0; f < faces_.size(); ++f) {
      if (!faces_[f].alive) continue;
      update_plane(f);
      // The plane goes through the vertex farthest along the normal, so it
      // supports the hull: no vertex is outside any face's plane, even where
      // rounding has tilted a long thin face's fitted plane above a vertex
      // far away (in hulls thinner than about a thousand tolerances). All
      // vertices are scanned while that costs at most about as much as the
      // construction; beyond, the search climbs from the face's own vertex
      // to a neighbour farther out until none is, which on a convex hull
      // ends at the farthest.
      std::uint32_t top = edges_[faces_[f].edge].origin;
      double height = dot(faces_[f].normal, point(top));
      if (scan) {
        for (const std::uint32_t p : out.vertex_points) {
          const double d = dot(faces_[f].normal, point(p));
          if (d > height) {
            height = d;
            top = p;
          }
        }
      }
      for (bool climbed = true; climbed;) {
        climbed = false;
        const std::uint32_t first = leaving[top];
        std::uint32_t e = first;
        do {
          const double d = dot(faces_[f].normal, point(dest(e)));
          if (d > height) {
            height = d;
            top = dest(e);
            climbed = true;
            break;
          }
          e = edges_[edges_[e].prev].twin;
        } while (e != first);
      }
      out.supports.push_back(vertex_of[top]);
      std::uint32_t h = faces_[f].edge;
      do {
        out.face_vertices.push_back(vertex_of[edges_[h].origin]);
        const std::uint32_t t = edges_[h].twin;
        if (h < t) out.edges.push_back({vertex_of[edges_[h].origin], vertex_of[dest(h)], face_of[f], face_of[edges_[t].face]});
        h = edges_[h].next;
      } while (h != faces_[f].edge);
      out.face_offsets.push_back(static_cast<std::uint32_t>(out.face_vertices.size()));
      out.normals.push_back(faces_[f].normal);
    }
  }

  std::span<const vec3<double>> points_;
  double tolerance_ = 0;
  std::vector<half_edge> edges_;
  std::vector<face_record> faces_;
  std::vector<std::uint32_t> next_conflict_;  // per point: the next point on its face's list
  std::vector<std::uint32_t> point_mark_;     // per point: == stamp_ when seen this step
  std::vector<std::uint32_t> pool_mark_;      // per point: == stamp_ when reassigned this step
  std::vector<std::uint32_t> horizon_from_;   // per point: the boundary edge leaving it
  std::vector<std::uint8_t> on_hull_;         // per point: a vertex of the current hull
  std::vector<std::uint8_t> removed_before_;  // per point: it has left the hull once
  std::vector<std::uint8_t> welded_;          // per point: a near duplicate of an earlier point
  std::vector<std::uint32_t> bucket_, chain_; // scratch of weld
  std::vector<std::uint8_t> is_near_;         // per point: listed in near_
  std::vector<std::uint32_t> near_;           // dropped points within the tolerance outside
  std::vector<std::uint32_t> near_best_;      // scratch of sweep_near
  std::vector<double> near_distance_;
  std::uint32_t stamp_ = 0;                   // one per added point
  bool always_strict_ = false;                // is_reflex strictly, whatever the angle
  // Scratch, kept to reuse its memory.
  std::vector<std::uint32_t> pending_, stack_, visible_, boundary_, horizon_, cone_, worklist_, touched_, orphans_, region_, reflex_;
};

using quickhull = basic_quickhull<>;

}  // namespace impulse::detail
