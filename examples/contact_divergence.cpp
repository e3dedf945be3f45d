// Prints how the penetration (EPA) normal and the volume-based normal respond
// to tiny motions in the contact-divergence scenario of the seed's Figure A.7.
//   build/examples/contact_divergence [max_shift] [samples]
#include <cstdio>
#include <cstdlib>

#include "divergence_scenario.hpp"

int main(int argc, char** argv) {
  const double max_shift = argc > 1 ? std::atof(argv[1]) : 1e-3;
  const int samples = argc > 2 ? std::atoi(argv[2]) : 11;
  if (!(max_shift > 0 && max_shift < 0.05) || samples < 2) {
    std::fprintf(stderr, "usage: contact_divergence [max_shift in (0, 0.05)] [samples >= 2]\n");
    return 2;
  }
  const auto sweep = gjkdem::examples::divergence_sweep(max_shift, samples);
  std::printf("%12s %12s %14s %17s %14s\n", "shift (m)", "EPA depth", "EPA normal deg", "volume normal deg", "overlap m^3");
  double epa_jump = 0, vol_jump = 0;
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const auto& s = sweep[i];
    std::printf("%12.6f %12.6f %14.3f %17.3f %14.6e\n", s.shift, s.depth, s.epa_deg, s.volume_deg, s.volume);
    if (i > 0) {
      epa_jump = std::fmax(epa_jump, std::fabs(s.epa_deg - sweep[i - 1].epa_deg));
      vol_jump = std::fmax(vol_jump, std::fabs(s.volume_deg - sweep[i - 1].volume_deg));
    }
  }
  const double step = 2 * max_shift / (samples - 1);
  std::printf("\nlargest change between neighbouring samples (%.2e m apart): EPA normal %.3f deg, volume normal %.3f deg\n",
              step, epa_jump, vol_jump);
  return 0;
}
