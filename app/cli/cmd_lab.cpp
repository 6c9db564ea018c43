// simsols lab: the desktop lab (a window; needs a display).
//
//   simsols lab [SCENE.toml] [--script FILE] [--size WxH]
#include <cstdio>

#include "app/cli/commands.h"
#include "solver/common/errors.h"
#include "render/view/frames.h"
#include "app/lab/lab_app.h"

namespace simsols {

int run_lab(const LabOptions& options) {
  if (!LabWindow::display_available())
    throw UsageError("io", "", 0, "DISPLAY",
                     "no display: the lab needs a window (use `simsols run` headless, or "
                     "xvfb-run for scripted sessions)");
  LabApp app(options);
  return app.run();
}

CommandRunner add_lab_command(CLI::App& app) {
  auto opt = std::make_shared<LabOptions>();
  auto size = std::make_shared<std::string>("1400x860");
  CLI::App* cmd = app.add_subcommand("lab", "The desktop lab: operate a shear box, oedometer or triaxial cell live");
  cmd->add_option("scene", opt->scene, "Scene file with an apparatus (default: the shear box's 6.35 mm preset)");
  cmd->add_option("--script", opt->script, "Run the commands of this file (see docs/lab.md)");
  cmd->add_option("--size", *size, "Window size WxH")->capture_default_str();
  return [opt, size] {
    std::tie(opt->width, opt->height) = parse_frame_size(*size, "--size");
    return run_lab(*opt);
  };
}

}  // namespace simsols
