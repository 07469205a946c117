#pragma once
// The viewer's screenshot for the report (tcbench reproduce): the stack of
// plates20 under full beside interruptible at full-work/3 (implicit contact,
// seed 0; the stack sweep records their replays), at their last recorded
// frame, taken by viewer/screenshot.mjs in headless chromium. Writes
// DIR/viewer/plates20_full_interruptible.png and DIR/viewer/viewer.json, which
// says what the picture shows, or why there is none (no such runs, no node
// or browser here); the report draws from both. Never fails the reproduce:
// a missing screenshot is said, not fatal.

#include <filesystem>

#include <nlohmann/json.hpp>

namespace tcb::cli {

/// The two run directories beneath `sweep_dir` (its runs/*/run.json) the
/// screenshot shows: [full, interruptible @ full-work/3] of plates20, implicit,
/// seed 0, with a replay; an empty array when either is missing.
nlohmann::json viewer_screenshot_runs(const std::filesystem::path& sweep_dir);

/// Makes the screenshot of `results_dir`/1_stack with `tcbench` (this
/// executable), and returns what viewer.json records.
nlohmann::json make_viewer_screenshot(const std::filesystem::path& results_dir, const std::filesystem::path& tcbench);

}  // namespace tcb::cli
