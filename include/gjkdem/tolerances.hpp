#pragma once
// Every default tolerance of gjkdem, in one place. See docs/tolerances.md for how
// the values were chosen. Geometric tolerances are relative to the size of the
// pair (the larger bounding diameter of the two shapes) unless the name says
// otherwise; QuerySettings copies them so each call may override them.
#include <cstddef>

#include "gjkdem/math/real.hpp"

namespace gjkdem {

/// GJK stops when the duality gap |v|^2 - v.w falls below kGjkRelTol * |v|^2
/// (relative; v = closest point of the simplex, w = newest support point), so the
/// distance is known to about kGjkRelTol/2 relative. Raising it saves iterations
/// on curved shapes and loosens distances; below ~1e-14 it is round-off.
inline constexpr Real kGjkRelTol = 1e-11;

/// Absolute companion of kGjkRelTol for near-touching pairs, relative to the pair
/// size: GJK also stops once the distance is bracketed to kGjkAbsTol * size.
inline constexpr Real kGjkAbsTol = 1e-13;

/// Cores closer than kGjkTouchTol * size count as touching and go to EPA
/// (relative). It sits well above double round-off (1e-16 * coordinates) and far
/// below the 1e-9 accuracy the query format asks for.
inline constexpr Real kGjkTouchTol = 1e-13;

/// Hard cap on GJK iterations. Polytopes finish in tens; smooth curved shapes
/// converge linearly and may take a hundred at kGjkRelTol. Reaching the cap gives
/// status MaxIterations with the best bound found.
inline constexpr int kMaxGjkIterations = 256;

/// EPA stops when the support in the closest face's normal lies within
/// kEpaRelTol * depth + kEpaAbsTol * size of that face (relative).
inline constexpr Real kEpaRelTol = 1e-11;
inline constexpr Real kEpaAbsTol = 1e-13;

/// EPA buffers are fixed-size (no heap in a query). When they fill up EPA returns
/// the best face it has with status OutOfMemory rather than failing.
inline constexpr int kEpaMaxVertices = 256;
inline constexpr int kEpaMaxFaces = 2 * kEpaMaxVertices;
inline constexpr int kMaxEpaIterations = kEpaMaxVertices - 4;
/// EPA's closest face may not come closer than the closest face seen before
/// by more than this (x size): it only does when round-off turned a sliver
/// face inside out, and EPA then answers with the face before.
inline constexpr Real kEpaMonotoneSlack = 1e-9;

/// Penetration of smooth shapes: when EPA's buffers fill before it converges,
/// a Newton polish of the normal on the sphere stops once the tangential part
/// of the support point is below kPolishRelTol * size (relative), or after
/// kMaxPolishIterations steps (each costs five support calls).
inline constexpr Real kPolishRelTol = 1e-12;
inline constexpr int kMaxPolishIterations = 30;

/// Hull triangles whose unit normals differ by less than this (length of the
/// difference, ~radians) and whose planes agree within kHullRelTol merge into
/// one facet. Raising it merges gently curved surfaces into flat faces.
inline constexpr Real kHullParallelTol = 1e-9;

/// A face of A counts as lying on B's boundary (a shared face of aligned
/// bodies) when its normal and B's face normal agree to within this cosine
/// (and its vertices are kOverlapRelTol-close to B's plane).
inline constexpr Real kSharedFaceCos = 1 - 1e-9;

/// Manifolds: A's face stays the reference unless B's face is better aligned
/// with the contact normal by more than this (a cosine difference): no
/// flip-flop between nearly equal faces from one step to the next.
inline constexpr Real kManifoldReferenceBias = 1e-3;

/// Newton polish: finite-difference step (radians) for the Hessian of the
/// support function on the sphere. Smaller is more round-off, larger more bias.
inline constexpr Real kPolishStep = 1e-5;

/// The polish's step along a kinked valley (polish_impl.hpp) samples the
/// gradients on either side at spreads from the trust radius down to
/// kPolishMinSpread (radians), and its line search tries lengths down to
/// kPolishShortestStep times the spread; the trust radius never falls below
/// kPolishMinRadius (radians), so that a polish stuck at a point can still move.
inline constexpr Real kPolishMinSpread = 1e-12;
inline constexpr Real kPolishShortestStep = 1e-3;
inline constexpr Real kPolishMinRadius = 1e-12;

/// Penetration witnesses of cores with flat or straight parts
/// (polish_impl.hpp): support sets are sampled at directions tilted by this
/// angle (radians; a curved side moves the sample by about angle x radius),
/// and points within kWitnessProbeTol * size of the other set's hull count
/// as in it.
inline constexpr Real kWitnessProbeAngle = 1e-9;
inline constexpr Real kWitnessProbeTol = 1e-8;

/// A mesh is convex when its enclosed volume matches its hull's to this
/// (relative); above it the mesh is replaced by its hull with a warning.
inline constexpr Real kMeshConvexRelTol = 1e-9;

/// Input quaternions may be off unit length by this (printed rounding); the
/// reader normalises them, and refuses anything further off.
inline constexpr Real kUnitQuaternionTol = 1e-6;

/// Restitution calibration of the damped laws: bisection stops when the
/// damping parameter is bracketed to this (dimensionless).
inline constexpr Real kDampingCalibrationTol = 1e-9;

/// The calibration integrates the dimensionless impact (RK4) in steps of
/// this (the undamped contact lasts about 3.1 time units: some 15,000 steps
/// of a smooth force).
inline constexpr Real kCalibrationTimeStep = 2e-4;

/// Overlap clipping: a vertex within kOverlapRelTol * size of a clipping plane
/// counts as on it (relative). Keeps slivers of round-off from becoming faces.
inline constexpr Real kOverlapRelTol = 1e-12;

/// Overlap clipping: a face that a plane cuts while lying within
/// kOverlapGrazeRelTol * size of it (and within 10 times this times the
/// smaller body's volume / size^2, for slivers) becomes part of that plane's
/// cut face (relative). Cutting it would place the crossings by dividing differences of
/// round-off; raising it moves more volume (at most this times the face's area).
inline constexpr Real kOverlapGrazeRelTol = 1e-8;

/// Surface overlaps (surface_overlap.hpp): a piece of A ∩ B whose volume is
/// below kPatchMinRelVolume of the smaller solid's is no patch (the symbolic
/// perturbation leaves slivers of rounding size where faces only touch).
/// Relative to a volume; the shared samples' volume tolerance is 1e-9.
inline constexpr Real kPatchMinRelVolume = 1e-11;

/// Surface grains in the DEM (surface_contact.hpp): a patch keeps the slot
/// (and springs) of last step's patch of the pair whose centroid lies within
/// kPatchMatchRel of the smaller body's equivalent radius (the sphere of
/// equal volume). Patches move far less in a step; distinct patches of one
/// pair (the two hooks of interlocked C's) lie about a body's size apart.
inline constexpr Real kPatchMatchRel = 0.25;

/// Surface grains: a piece of an overlap whose contact area |S_A| is below
/// kEngulfedAreaRel times its volume^(2/3) has one solid wholly inside the
/// other (|S_A| is zero, or rounding noise: 1e-17 of the piece's size
/// measured for an icosahedron inside another). The run stops naming the
/// pair. A real contact's |S_A| is at least of the order of V^(2/3).
inline constexpr Real kEngulfedAreaRel = 1e-6;
/// A run warns, once, of a contact deeper than this times the smaller radius
/// of curvature of its bodies: the contact laws are made for small overlaps
/// (a press crushing soft fragments had one 0.7 mm into the floor, silently).
inline constexpr Real kLawRangeRel = 0.1;

/// A bonded assembly's bonds must be at least this fraction of the stiffness
/// of a bar of the material spanning two pieces (E / spacing, Pa/m), in
/// tension and in shear: bonded pieces do not touch, and a softer bond lets
/// them sink into each other unopposed.
inline constexpr Real kMinBondStiffnessRel = 1e-3;

/// Two convex bodies whose contact is deeper than this times the smaller
/// one's radius of curvature are tested for passing through each other (a
/// centre inside the other body: the run stops). A shallower one with a
/// centre inside is a thin fragment squeezed, deep but not through (the
/// press example has one 50% of its radius in at its end; kLawRangeRel
/// warns of it). Two spheres' centres lie inside each other only deeper.
inline constexpr Real kDeepOverlapRel = 1.0;
/// Surface grains' deep points (shape/deep_points.hpp), where a body passing
/// through one is seen as a convex body's centre sees it: candidates at the
/// centres of a kDeepPointGrid^3 grid over its box (and its centroid), at
/// most kDeepPointsMax kept, each at least kDeepPointRel of the deepest's
/// depth (a torus keeps points along its core, an L one per arm). A patch
/// of a surface grain is tested when its mean depth (volume over area)
/// passes kDeepReachRel of the shallower deep point of the pair: a contact
/// reaching a point that deep is far beyond any law's range (kLawRangeRel),
/// and a pointed body reaches it with a mean depth of a third of it.
inline constexpr int kDeepPointGrid = 4;
inline constexpr std::size_t kDeepPointsMax = 8;
inline constexpr Real kDeepPointRel = 0.5;
inline constexpr Real kDeepReachRel = 0.25;
/// 2 kDeepPointsMax candidates, spread (the deepest, then each the farthest
/// from those taken), are deepened by a compass search of at most
/// kDeepPointSteps steps, ending when the step falls below kDeepPointStepRel
/// of its depth.
inline constexpr int kDeepPointSteps = 200;
inline constexpr Real kDeepPointStepRel = 1e-2;
/// Such a piece is the smaller solid wholly inside the other when its volume
/// is that solid's within this (relative); a smaller piece is one solid
/// passed through the other.
inline constexpr Real kWhollyInsideVolumeRel = 1e-6;

/// Surface overlaps: an edge of the other surface is tested exactly for
/// lying along an edge's line only when the squared sines of its ends'
/// angles off the line sum below this (a screen: rounding gives ~1e-32 for
/// points on the line; the exact test decides).
inline constexpr Real kCollinearScreenRel2 = 1e-20;

/// The area-weighted contact normal is reported only when |S_A - S_B| exceeds
/// kContactNormalRelTol times the overlap's total surface area (relative): below
/// it the normal is undefined (one shape inside the other, shared faces).
inline constexpr Real kContactNormalRelTol = 1e-9;

/// Manifolds: a face is used for face contact when its normal is within this
/// cosine of the contact normal; below it (edge-edge, vertex contacts) a single
/// point is reported. Relative (a cosine).
inline constexpr Real kManifoldFaceCos = 0.95;

/// Contact clustering: contacts of one pair closer than kContactMergeRelDist *
/// size (relative) with normals within kContactMergeCos (a cosine) are one
/// contact. Raise the distance to merge contacts of coarse wall meshes.
inline constexpr Real kContactMergeRelDist = 1e-3;
inline constexpr Real kContactMergeCos = 0.999;

/// DEM wall meshes: contacts of one body with pieces of one wall whose normals
/// agree within this cosine (about 25 degrees) and lie within the body's
/// radius are one contact. Looser than kContactMergeCos because the normals of
/// a body straddling two coplanar triangles tilt near the shared edge.
inline constexpr Real kWallMergeCos = 0.9;

/// DEM wall meshes: a contact with a piece is in the piece's face region when
/// its normal lies within this cosine of the triangle's normal; otherwise it
/// touches an edge or a corner, and beside a deeper face-region contact of
/// the same body and wall (within the body's radius) it is the same touch
/// seen over a seam, and is dropped. Round-off of GJK's normals on a face
/// is far below it; a real edge contact tilts by more.
inline constexpr Real kWallFaceRegionCos = 1 - 1e-9;

/// DEM worlds: an explicit body may start touching another body or a wall
/// (stacks do), but not overlapping it by more than this times its bounding
/// radius (relative): WorldBuilder refuses that start, naming the two.
inline constexpr Real kStartOverlapRelTol = 1e-9;

/// The energy guard (run.cpp) lets unexplained energy below the energy of
/// lifting every moving body by this fraction of its reach pass as round-off
/// (relative): a bed at rest gains nothing larger.
inline constexpr Real kEnergyGuardFloorRel = 1e-9;

/// A domain layout's regions are half-open: their top is raised this far
/// (relative) above the highest centre, so that its body lies inside.
inline constexpr Real kLayoutTopRelPad = 1e-12;

/// Random rotations and polyhedra draw directions from a normal
/// distribution; a draw shorter than this is drawn again (its direction
/// would be round-off).
inline constexpr Real kRandomDirectionMinNorm = 1e-6;

/// A size distribution's mass fractions must add up to 1 within this
/// (printed fractions such as 0.333 three times are refused).
inline constexpr Real kMassFractionSumTol = 1e-6;

/// Input limit: coordinates, positions and scaled meshes beyond this
/// magnitude (m) are refused by every reader (queries, scenes): squares of
/// such numbers, and their differences, stay finite and resolvable.
inline constexpr Real kMaxCoordinate = 1e100;
/// A closed surface whose volume is at most this fraction of the sum over
/// its triangles of |a - o| |b - o| |c - o| (o its first vertex) encloses no
/// volume double precision resolves (flat, or thinner than about 1e-12 of
/// its size): refused, as its volume's sign is round-off.
inline constexpr Real kFlatSurfaceRel = 1e-12;
/// The smallest mesh a scale may leave (its largest |coordinate|, m): below
/// it the vertices' differences underflow and the mesh reads as flat.
inline constexpr Real kMinMeshSize = 1e-100;

/// A run of duration T in steps of dt takes ceil(T / dt - kStepCountRelTol)
/// steps (relative, in steps): a duration that is a whole number of steps up
/// to round-off does not get one step more.
inline constexpr Real kStepCountRelTol = 1e-9;

/// Polytopes with more hull vertices than this hill-climb over the vertex
/// adjacency; smaller ones scan every vertex (faster below this size).
inline constexpr int kHillClimbMinVertices = 64;

/// Solid polytopes with at least this many hull triangles keep a slot for
/// their boundary surface (hull_surface, surface.hpp), made on first use:
/// their overlaps may then be found as surfaces' (below).
inline constexpr int kSurfaceRouteMinTriangles = 256;

/// Overlap of two such polytopes: when the planes of B that reach A's faces
/// times the corners of those faces exceed this, the clip (whose work that
/// product measures: every cutting plane rewrites every kept face) gives way
/// to the overlap of their surfaces (surface_overlap), whose work follows the
/// triangles that cross. Measured on hulls of one ellipsoid (a DEM bed's
/// grains) and on poly-many's unequal hulls (docs/tolerances.md).
inline constexpr double kClipWorkBeyondSurfaces = 40000;

/// Polytopes with at least this many (padded) vertices scan 4 at a time where
/// the processor has AVX2 (chosen at run time; the 2-wide SSE2 scan
/// elsewhere, and inlined below this size, where a call costs more than the
/// wider scan saves). Both give the same vertex.
inline constexpr int kWideScanMinVertices = 16;

/// Quickhull: a new face whose apex lies within kHullNeedleRel * (bounding
/// diagonal) of its base edge's line is a needle, and the face beyond that
/// edge joins the faces replaced when the needle would fold against it by
/// more than kHullRelTol (a needle magnifies a fold of round-off). Raising it
/// replaces faces around wider new faces too, where coplanar points can turn
/// the new face over.
inline constexpr Real kHullNeedleRel = 1e-6;

/// Points within kHullRelTol * (bounding diagonal) of a hull plane are treated as
/// on it (relative). Raising it merges more near-coplanar points away.
inline constexpr Real kHullRelTol = 1e-12;

/// Two parts of a compound may overlap by this much (relative to the larger
/// part's bounding diameter) and still count as touching: round-off in
/// parts meant to share a face, far below any overlap that would change the
/// mass properties measurably.
inline constexpr Real kCompoundOverlapRelTol = 1e-9;

/// Voronoi cells (shape/voronoi.hpp): a cell's faces are the facets within
/// kCellFaceRelTol * (the solid's size) of a bisector plane, and its walk
/// over the other sites stops once one lies beyond twice the cell's radius
/// plus 4 face tolerances plus kCellStopRoundoffRel * (the largest
/// coordinate): far above the round-off of the plane tests' dot products,
/// so the stop skips only planes the tests would skip.
inline constexpr Real kCellFaceRelTol = 1e-7;
inline constexpr Real kCellStopRoundoffRel = 1e-12;

}  // namespace gjkdem
