#include "app/experiment/shear_box/study_run.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <mutex>
#include <optional>
#include <thread>

#include "app/experiment/run_cost.h"
#include "app/experiment/shear_box/study_state.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

void report_case(const StudyCase& c, bool shear) {
  if (c.contact.ok)
    std::fprintf(stderr, "    contact: worst error %.3g %%\n", c.contact.worst());
  else
    std::fprintf(stderr, "    contact: failed: %s\n", c.contact.failure.c_str());
  if (!shear) return;
  if (c.shear.ok)
    std::fprintf(stderr, "    shear: phi_peak %.2f, phi_res %.2f, psi_max %.2f deg in %.1f s\n",
                 c.shear.peak_angle, c.shear.residual_angle, c.shear.dilatancy_angle,
                 c.shear.wall_seconds);
  else
    std::fprintf(stderr, "    shear: failed: %s\n", c.shear.failure.c_str());
}

// The contact checks have no specimen and no shear speed or skin: a run
// whose time step, precision, stiffness and effects an earlier run had
// (another member, the round-off twin) reuses that run's results.
ContactErrors contact_checks_of(const StudySettings& s, const std::vector<StudyCase>& done,
                                const std::shared_ptr<Device>& device) {
  for (const StudyCase& c : done)
    if (c.settings.dt_fraction == s.dt_fraction && c.settings.precision == s.precision &&
        c.settings.stiffness_scale == s.stiffness_scale && c.settings.rolling == s.rolling &&
        c.settings.damping == s.damping)
      return c.contact;
  return run_contact_checks(s, device);
}

// The pool (study_run.h): its workers take the cases in order.
class StudyPool {
 public:
  StudyPool(const StudyPreset& preset, const std::vector<StudySettings>& cases,
            std::vector<StudyCase> done, const StudyRunOptions& opt)
      : opt_(opt), preset_(preset), cases_(cases), results_(cases_.size()),
        first_(done.size()), next_(done.size()) {
    for (size_t i = 0; i < done.size(); ++i) results_[i] = std::move(done[i]);
  }

  StudyRunOutcome run() {
    t0_ = std::chrono::steady_clock::now();
    const int jobs = std::max(1, opt_.jobs);
    std::vector<std::shared_ptr<Device>> devices(static_cast<size_t>(jobs));
    for (auto& d : devices) d = opt_.open_device();  // one after the other
    {
      std::vector<std::jthread> workers;  // joined when the scope ends, also on a throw
      for (int k = 1; k < jobs; ++k) workers.emplace_back([this, d = devices[k]] { work(d); });
      work(devices[0]);
    }
    if (error_) std::rethrow_exception(error_);
    return {prefix().size(), cases_.size(), interrupted_};
  }

 private:
  std::vector<StudyCase> finished() const {  // in case order
    std::vector<StudyCase> f;
    for (const auto& r : results_)
      if (r) f.push_back(*r);
    return f;
  }
  std::vector<StudyCase> prefix() const {
    std::vector<StudyCase> f;
    for (const auto& r : results_) {
      if (!r) break;
      f.push_back(*r);
    }
    return f;
  }
  bool stop_asked() const { return opt_.stop_requested && opt_.stop_requested(); }

  // The next case to run, or nullopt when none is left or a stop was asked.
  std::optional<size_t> take() {
    std::lock_guard lock(mutex_);
    if (next_ >= cases_.size() || stop_asked() || error_) return std::nullopt;
    const size_t i = next_++;
    if (!opt_.quiet) announce(i);
    return i;
  }

  void announce(size_t i) const {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    const std::string eta =
        ran_ > 0 ? ", ETA " + human_seconds(elapsed / double(ran_) * double(cases_.size() - first_ - ran_))
                 : "";
    std::fprintf(stderr, "[study %zu/%zu] %s specimen, %s: %s, seed %d (elapsed %s%s)\n", i + 1,
                 cases_.size(), specimen_name(cases_[i].specimen), cases_[i].knob.c_str(),
                 cases_[i].label.c_str(), cases_[i].seed, human_seconds(elapsed).c_str(), eta.c_str());
  }

  void work(std::shared_ptr<Device> device) {
    try {
      while (const std::optional<size_t> i = take()) run_case(*i, device);
    } catch (...) {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = std::current_exception();
      failed_ = true;
    }
  }

  void run_case(size_t i, const std::shared_ptr<Device>& device) {
    StudyCase c;
    c.settings = cases_[i];
    std::vector<StudyCase> known;
    {
      std::lock_guard lock(mutex_);
      known = finished();
    }
    c.contact = contact_checks_of(cases_[i], known, device);
    // a checkpoint of this case from an interrupted study, whichever jobs wrote it
    fs::path checkpoint = study_case_checkpoint(opt_.out, i, 2);
    if (!fs::exists(checkpoint) && (opt_.jobs <= 1 || i == first_))
      checkpoint = study_case_checkpoint(opt_.out, i, 1);
    // stop on Ctrl-C, and when another worker failed (its error ends the study)
    const ShearCaseControl control{[this] { return stop_asked() || failed_.load(); },
                                   checkpoint.string(), device};
    if (preset_.shear) c.shear = run_shear_case(preset_, cases_[i], control);
    std::lock_guard lock(mutex_);
    if (c.shear.interrupted) {
      if (failed_) return;  // stopped for another worker's error: the error is the news
      interrupted_ = true;
      std::printf("study interrupted in case %zu/%zu (%s); its state is in %s\n", i + 1,
                  cases_.size(), cases_[i].label.c_str(), checkpoint.string().c_str());
      return;
    }
    fs::remove(checkpoint);
    if (!opt_.quiet) report_case(c, preset_.shear);
    results_[i] = c;
    ++ran_;
    std::vector<StudyCase> all = finished(), ordered = prefix();
    compare_to_reference(all);
    write_study_outputs(opt_.out, preset_, all);
    write_file_atomic((fs::path(opt_.out) / "study_state.txt").string(),
                      study_state_text(preset_, cases_, ordered));
  }

  const StudyRunOptions& opt_;
  const StudyPreset& preset_;
  const std::vector<StudySettings>& cases_;
  std::vector<std::optional<StudyCase>> results_;
  const size_t first_;  // finished before this invocation
  size_t next_;
  size_t ran_ = 0;  // finished by this invocation
  bool interrupted_ = false;
  std::exception_ptr error_;
  std::atomic<bool> failed_ = false;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace

fs::path study_case_checkpoint(const std::string& out, size_t i, int jobs) {
  return fs::path(out) /
         (jobs > 1 ? "case_checkpoint_" + std::to_string(i + 1) + ".bin" : "case_checkpoint.bin");
}

StudyRunOutcome run_study(const StudyPreset& preset, const std::vector<StudySettings>& cases,
                          std::vector<StudyCase> done, const StudyRunOptions& options) {
  return StudyPool(preset, cases, std::move(done), options).run();
}

std::vector<StudyCase> resumed_study_cases(const std::string& out, const StudyPreset& preset,
                                           const std::vector<StudySettings>& cases) {
  const fs::path state = fs::path(out) / "study_state.txt";
  if (!fs::exists(state))
    throw SceneError("io", state.string(), 0, "--resume",
                     "no study to resume here (a study writes this file after its first case)");
  std::ifstream in(state, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  std::vector<StudyCase> done = parse_study_state(text, state.string(), preset, cases);
  compare_to_reference(done);
  std::fprintf(stderr, "[study] resumed after %zu of %zu cases%s\n", done.size(), cases.size(),
               fs::exists(fs::path(out) / "case_checkpoint.bin")
                   ? " (the next one from its checkpoint)"  // jobs 1's name
                   : "");
  return done;
}

}  // namespace simsols
