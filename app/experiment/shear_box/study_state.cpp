#include "app/experiment/shear_box/study_state.h"

#include <cstdio>
#include <sstream>

#include "solver/common/errors.h"

namespace simsols {
namespace {

constexpr const char* kTag = "simsols-study-state 3";

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

std::string nums(std::initializer_list<double> v) {
  std::string s;
  char buf[40];
  for (double x : v) {
    std::snprintf(buf, sizeof buf, " %.17g", x);
    s += buf;
  }
  return s;
}

// Reads "key rest-of-line"; throws with the line number on a mismatch.
class LineReader {
 public:
  LineReader(const std::string& text, std::string path) : in_(text), path_(std::move(path)) {}
  std::istringstream expect(const std::string& key) {
    std::string line;
    ++line_;
    if (!std::getline(in_, line) || line.rfind(key, 0) != 0)
      fail("expected '" + key + "'");
    return std::istringstream(line.substr(key.size()));
  }
  std::string rest(const std::string& key) {
    std::istringstream s = expect(key);
    std::string r;
    std::getline(s, r);
    return r.empty() ? r : r.substr(1);
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw SceneError("bad_study_state", path_, line_, "",
                     what + " (a damaged file, or another study: use a new --out)");
  }

 private:
  std::istringstream in_;
  std::string path_;
  int line_ = 0;
};

// "specimen | knob | label | seed S perturbation P": a run's identity.
std::string identity(const StudySettings& s) {
  char buf[64];
  std::snprintf(buf, sizeof buf, " | seed %d perturbation %.17g%s", s.seed, s.perturbation,
                s.perturb_at_shear ? " at shear" : "");
  return std::string(specimen_name(s.specimen)) + " | " + one_line(s.knob) + " | " +
         one_line(s.label) + buf;
}

std::string curve_text(const ShearResult& s) {
  std::string o = std::to_string(s.curve_mm.size());
  char buf[64];
  for (size_t i = 0; i < s.curve_mm.size(); ++i) {
    std::snprintf(buf, sizeof buf, " %.9g %.9g", s.curve_mm[i], s.curve_ratio[i]);
    o += buf;
  }
  return o;
}

}  // namespace

std::string study_state_text(const StudyPreset& preset, const std::vector<StudySettings>& cases,
                             const std::vector<StudyCase>& done) {
  std::ostringstream o;
  o << kTag << "\npreset " << preset.name << "\npoured_box_scale"
    << nums({preset.poured_box_scale}) << "\ncases " << cases.size() << "\nfinished "
    << done.size() << '\n';
  for (const StudyCase& c : done) {
    const ContactErrors& k = c.contact;
    const ShearResult& s = c.shear;
    o << "case " << identity(c.settings) << '\n'
      << "contact " << k.ok
      << nums({k.overlap, k.force, k.duration, k.restitution, k.rolling}) << '\n'
      << "contact_failure " << one_line(k.failure) << '\n'
      << "shear " << s.ok
      << nums({s.peak_angle, s.residual_angle, s.dilatancy_angle, s.wall_seconds,
               s.particle_steps_per_second, double(s.steps), double(s.list_builds),
               double(s.particles)})
      << '\n'
      << "shear_failure " << one_line(s.failure) << '\n'
      << "curve " << curve_text(s) << '\n';
  }
  return o.str();
}

std::vector<StudyCase> parse_study_state(const std::string& text, const std::string& path,
                                         const StudyPreset& preset,
                                         const std::vector<StudySettings>& cases) {
  LineReader r(text, path);
  r.expect(kTag);
  if (r.rest("preset") != preset.name) r.fail("written by another --preset");
  double scale = 0;
  if (!(r.expect("poured_box_scale") >> scale) || scale != preset.poured_box_scale)
    r.fail("written with another --box-scale");
  size_t n = 0, finished = 0;
  // the finished cases must be the first of `cases` (each checked below); a
  // study whose case list grew at its end continues
  if (!(r.expect("cases") >> n)) r.fail("a bad count of cases");
  if (!(r.expect("finished") >> finished) || finished > n || finished > cases.size())
    r.fail("more finished cases than this study has (--knob, --specimen?)");
  std::vector<StudyCase> done(finished);
  for (size_t i = 0; i < finished; ++i) {
    StudyCase& c = done[i];
    c.settings = cases[i];
    if (r.rest("case") != identity(cases[i]))
      r.fail("case " + std::to_string(i + 1) + " is not '" + identity(cases[i]) + "' (--ensemble?)");
    ContactErrors& k = c.contact;
    ShearResult& s = c.shear;
    if (!(r.expect("contact") >> k.ok >> k.overlap >> k.force >> k.duration >> k.restitution >>
          k.rolling))
      r.fail("malformed contact results");
    k.failure = r.rest("contact_failure");
    double steps = 0, builds = 0, particles = 0;
    if (!(r.expect("shear") >> s.ok >> s.peak_angle >> s.residual_angle >> s.dilatancy_angle >>
          s.wall_seconds >> s.particle_steps_per_second >> steps >> builds >> particles))
      r.fail("malformed shear results");
    s.steps = static_cast<long long>(steps);
    s.list_builds = static_cast<long long>(builds);
    s.particles = static_cast<int>(particles);
    s.failure = r.rest("shear_failure");
    std::istringstream curve = r.expect("curve");
    size_t points = 0;
    if (!(curve >> points) || points > 100000) r.fail("malformed curve");
    s.curve_mm.resize(points);
    s.curve_ratio.resize(points);
    for (size_t k = 0; k < points; ++k)
      if (!(curve >> s.curve_mm[k] >> s.curve_ratio[k])) r.fail("malformed curve");
  }
  return done;
}

}  // namespace simsols
