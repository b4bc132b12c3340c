#include "studies/claim_variants.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>

#include "batch/parallel_runner.hpp"
#include "observe/simulate.hpp"

namespace asperity {

std::string eta_variant_label(double eta) {
  char label[32];
  std::snprintf(label, sizeof label, "eta=%g", eta);
  return label;
}

std::vector<ClaimVariant> paper_claim_variants() {
  std::vector<ClaimVariant> v;
  for (double eta : kClaimEtaScan) {
    v.push_back({eta_variant_label(eta), [eta](Scene& s) { s.model.eta = eta; }});
  }
  v.push_back({"c_min=1e-5", [](Scene& s) { s.model.c_min = 1e-5; }});
  v.push_back({"equal_areas", [](Scene& s) {
                 auto& a = s.experiment.junctions.area_m2;
                 double sum = 0;
                 for (double x : a) sum += x;
                 a.assign(a.size(), sum / static_cast<double>(a.size()));
                 s.experiment.junctions.x_m.clear();
                 s.experiment.junctions.y_m.clear();
                 s.experiment.measured.reset();
                 s.stop.at_first_peak = true;
               }});
  v.push_back({"circular", [](Scene& s) { s.model.junction_shape = JunctionShape::circular; }});
  v.push_back({"area_law=always", [](Scene& s) { s.model.area_law = AreaLaw::always; }});
  // Claim 7 needs the explicit solver, which measures f/(σA) at every junction and step; at
  // C_t = 100 it costs about a minute per simulated second here, so a window of the loading.
  v.push_back({kReferenceVariantLabel,
               [](Scene& s) {
                 s.solver.method = SolverMethod::reference;
                 s.solver.Ct = 100;
                 s.stop.time = 0.25;  // the first slips start near 0.19 s on the smallest stand-in
                 s.stop.cycles = -1;
                 s.output.series.clear();
               },
               false});
  return v;
}

std::vector<VariantRun> run_variants(const std::vector<Scene>& base, const std::vector<ClaimVariant>& variants,
                                     int threads, const std::function<void(std::size_t, std::size_t)>& done) {
  struct Job {
    std::size_t scene, variant;
  };
  std::vector<Job> jobs;
  for (std::size_t v = 0; v < variants.size(); ++v)
    for (std::size_t s = 0; s < base.size(); ++s)
      if (variants[v].all_experiments || s == 0) jobs.push_back({s, v});
  // Longest first: the reference window dominates.
  std::stable_sort(jobs.begin(), jobs.end(), [&](const Job& a, const Job& b) {
    return !variants[a.variant].all_experiments && variants[b.variant].all_experiments;
  });
  std::vector<VariantRun> out(jobs.size());
  ParallelRunner(std::max(1, threads))
      .for_each(
          jobs.size(),
          [&](std::size_t j) {
            Scene s = base[jobs[j].scene];
            const ClaimVariant& v = variants[jobs[j].variant];
            v.apply(s);
            s.output.series.clear();  // only observables are needed
            out[j].experiment = s.experiment.name;
            out[j].label = v.label;
            try {
              out[j].obs = simulate(s).obs;
            } catch (const std::exception& e) {
              out[j].error = e.what();
            }
          },
          done);
  return out;
}

}  // namespace asperity
