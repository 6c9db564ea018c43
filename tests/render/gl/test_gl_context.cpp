// The headless EGL display order (render/gl/gl_context.h): a hardware EGL
// device (headless NVIDIA) before Mesa's surfaceless llvmpipe, so the GL
// context can sit on the OpenCL GPU and share buffers with it; software
// devices only after surfaceless; the default display last. The order is a
// pure function of what EGL lists, checked here on made-up inventories, and
// the context made on this machine comes from the first display of the
// order for this machine's inventory (on a machine without a GPU: EGL
// surfaceless).
#include <gtest/gtest.h>

#include <cstdio>

#include "render/gl/gl_context.h"

using namespace simsols::render;

namespace {

using Kind = EglDisplayChoice::Kind;

EglDisplayChoice device(int i) { return {Kind::Device, i}; }
const EglDisplayChoice kSurfaceless{Kind::Surfaceless};
const EglDisplayChoice kDefault{Kind::Default};

EglDeviceInfo hardware(const std::string& name) { return {false, name}; }
EglDeviceInfo software() { return {true, "software"}; }

std::string labels(const std::vector<EglDisplayChoice>& order, const EglInventory& inv) {
  std::string s;
  for (const EglDisplayChoice& c : order) s += (s.empty() ? "" : " | ") + egl_display_label(c, inv);
  return s;
}

}  // namespace

TEST(EglDisplayOrder, HardwareDeviceComesBeforeSurfaceless) {
  const EglInventory inv{true, {hardware("NVIDIA Corporation NVIDIA H200")}};
  const std::vector<EglDisplayChoice> want{device(0), kSurfaceless, kDefault};
  EXPECT_EQ(egl_display_order(inv, EglPreference::Hardware), want)
      << labels(egl_display_order(inv, EglPreference::Hardware), inv);
}

TEST(EglDisplayOrder, SoftwareDevicesAreSkippedInTheHardwarePass) {
  // Mesa lists its swrast device beside a GPU's; it comes after surfaceless.
  const EglInventory inv{true, {software(), hardware("NVIDIA"), software(), hardware("second")}};
  const std::vector<EglDisplayChoice> want{device(1), device(3), kSurfaceless,
                                           device(0), device(2), kDefault};
  EXPECT_EQ(egl_display_order(inv, EglPreference::Hardware), want)
      << labels(egl_display_order(inv, EglPreference::Hardware), inv);
}

TEST(EglDisplayOrder, WithoutHardwareSurfacelessComesFirst) {
  // A machine without a GPU (Mesa: one software device, the surfaceless
  // platform): llvmpipe through surfaceless, as before hardware came first.
  const EglInventory inv{true, {software()}};
  const std::vector<EglDisplayChoice> want{kSurfaceless, device(0), kDefault};
  EXPECT_EQ(egl_display_order(inv, EglPreference::Hardware), want)
      << labels(egl_display_order(inv, EglPreference::Hardware), inv);
}

TEST(EglDisplayOrder, SurfacelessPreferenceKeepsTheOlderOrder) {
  const EglInventory inv{true, {hardware("NVIDIA"), software()}};
  const std::vector<EglDisplayChoice> want{kSurfaceless, device(0), device(1), kDefault};
  EXPECT_EQ(egl_display_order(inv, EglPreference::Surfaceless), want)
      << labels(egl_display_order(inv, EglPreference::Surfaceless), inv);
}

TEST(EglDisplayOrder, DefaultDisplayIsAlwaysLast) {
  // NVIDIA alone (no Mesa): its devices, then the default display.
  const EglInventory nvidia{false, {hardware("NVIDIA")}};
  EXPECT_EQ(egl_display_order(nvidia, EglPreference::Hardware),
            (std::vector<EglDisplayChoice>{device(0), kDefault}));
  const EglInventory nothing{false, {}};
  for (EglPreference p : {EglPreference::Hardware, EglPreference::Surfaceless})
    EXPECT_EQ(egl_display_order(nothing, p), std::vector<EglDisplayChoice>{kDefault});
}

TEST(EglDisplayOrder, LabelsNameTheDisplay) {
  const EglInventory inv{true, {hardware("NVIDIA Corporation NVIDIA H200, /dev/dri/card1"),
                                hardware("")}};
  EXPECT_EQ(egl_display_label(device(0), inv),
            "EGL device 0 (NVIDIA Corporation NVIDIA H200, /dev/dri/card1)");
  EXPECT_EQ(egl_display_label(device(1), inv), "EGL device 1 (unnamed)");
  EXPECT_EQ(egl_display_label(kSurfaceless, inv), "EGL surfaceless");
  EXPECT_EQ(egl_display_label(kDefault, inv), "EGL default display");
}

// This machine: the context comes from the first display of the order, and
// its description says which.
TEST(EglContext, UsesTheFirstDisplayOfTheOrder) {
  const EglInventory inv = egl_inventory();
  for (EglPreference p : {EglPreference::Hardware, EglPreference::Surfaceless}) {
    const std::vector<EglDisplayChoice> order = egl_display_order(inv, p);
    SCOPED_TRACE(labels(order, inv));
    HeadlessOptions options;
    options.backend = GlBackend::Egl;
    options.egl = p;
    std::unique_ptr<GlContext> ctx;
    ASSERT_NO_THROW(ctx = create_headless_context(options));
    std::printf("%s\n", ctx->description().c_str());
    EXPECT_EQ(ctx->description().rfind(egl_display_label(order.front(), inv) + ": ", 0), 0u)
        << ctx->description();
    EXPECT_NE(ctx->share_handles().egl_display, 0);
  }
}
