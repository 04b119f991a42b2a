// `tetlod view` run in the background with a script, in an output directory of its
// own, for tests that act on the window from outside (X events) while it runs.
#pragma once

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "render/image.h"

namespace tetlod::test {

class BackgroundViewer {
 public:
  // Starts `tetlod view MESH --size SIZE --script s.script` in a fresh directory
  // TETLOD_TEST_OUTPUT_DIR/name, the script being `script`. Its output goes to
  // log.txt and its exit code to rc.txt. False if the shell could not start it.
  bool start(const std::string& name, const std::string& mesh, const std::string& script,
             const std::string& size = "800x600") {
    dir_ = std::filesystem::path(TETLOD_TEST_OUTPUT_DIR) / name;
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "s.script") << script;
    const std::string command = "cd '" + dir_.string() + "' && (" + TETLOD_BINARY + " view '" +
                                mesh + "' --size " + size +
                                " --script s.script "
                                ">log.txt 2>&1; echo $? >rc.txt) &";
    return std::system(command.c_str()) == 0;
  }

  const std::filesystem::path& dir() const { return dir_; }

  // Waits until the viewer has written `file` (in its directory).
  bool wait_for(const std::string& file, std::chrono::seconds limit = std::chrono::seconds(60)) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
      if (std::filesystem::exists(dir_ / file)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }

  // Waits for the viewer to end; its exit code, or -1 if it did not end in time.
  int finish(std::chrono::seconds limit = std::chrono::seconds(60)) {
    if (!wait_for("rc.txt", limit)) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // rc.txt fully written
    std::ifstream rc(dir_ / "rc.txt");
    int exit_code = -1;
    rc >> exit_code;
    return exit_code;
  }

  // A screenshot in its directory (empty if it cannot be read).
  render::Image load(const std::string& name) const {
    render::Image image;
    if (!render::read_png((dir_ / name).string(), &image).ok()) return {};
    return image;
  }

  // Pixels of screenshots a and b (in its directory) that differ by more than 8.
  size_t differing_pixels(const std::string& a, const std::string& b) const {
    const render::Image image_a = load(a), image_b = load(b);
    if (image_a.width == 0 || image_b.width == 0) return 0;
    return render::compare_images(image_a, image_b, 8, nullptr).differing_pixels;
  }

 private:
  std::filesystem::path dir_;
};

}  // namespace tetlod::test
