#pragma once
// Outcome codes of the narrow-phase queries.
namespace gjkdem {

enum class GjkStatus {
  Separated,      ///< cores apart; distance converged within the tolerances
  Intersecting,   ///< cores overlap or touch (origin inside or on A - B)
  MaxIterations,  ///< cap reached: the distance is an upper bound, still usable
};

enum class EpaStatus {
  NotRun,         ///< cores did not overlap: no EPA needed
  Converged,      ///< depth within the EPA tolerances
  Touching,       ///< depth zero up to round-off; normal is one of the touching normals
  Degenerate,     ///< A - B is flat (e.g. coplanar triangles): depth 0, normal = its plane normal
  OutOfMemory,    ///< buffers full: best face so far (a lower bound), still usable
  MaxIterations,  ///< cap reached: best face so far
};

}  // namespace gjkdem
