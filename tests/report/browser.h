#pragma once
// Opening a report page in headless Chromium for the page tests: the DOM after load (the page marks
// on its body whether it rendered, how many script errors it counted and when its first frame was
// drawn), the browser's console log, and a screenshot read back with libpng.
#include <png.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace dresskit::test::browser {

/// Chromium's path: DRESSKIT_CHROMIUM, else the first of chromium, chromium-browser, google-chrome
/// on PATH; "" when there is none.
inline std::string find_chromium() {
  if (const char* given = std::getenv("DRESSKIT_CHROMIUM"))
    return std::filesystem::exists(given) ? given : "";
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');)
    for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
      const std::filesystem::path p = std::filesystem::path(dir) / name;
      if (::access(p.c_str(), X_OK) == 0) return p.string();
    }
  return "";
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Load {
  int code = -1;          ///< the browser's exit code (124: stopped by the time limit)
  std::string dom, log;   ///< the DOM after load; stderr with the console's lines
  std::string rendered;   ///< body data-rendered: "yes" once the 3D view drew its first frame
  int errors = -1;        ///< body data-errors: script errors the page counted
  double load_ms = -1.0;  ///< body data-load-ms: from navigation start to the first frame drawn
  std::vector<std::string> console_errors;  ///< console lines of uncaught errors or the page's own
};

/// Common flags: no sandbox (root in a container), software WebGL, a profile of its own (tests run
/// in parallel), a fixed window. Every run is bounded by `timeout`.
inline std::string chromium_command(const std::string& chromium, const std::string& profile,
                                    const std::string& what, const std::string& page, int seconds) {
  return "timeout -k 5 " + std::to_string(seconds) + " " + chromium +
         " --headless --no-sandbox --disable-gpu --use-angle=swiftshader "
         "--enable-unsafe-swiftshader"
         " --disable-dev-shm-usage --no-first-run --no-default-browser-check --hide-scrollbars"
         " --mute-audio "
         "--window-size=1280,900"
         " --user-data-dir=" +
         profile + " --enable-logging=stderr --v=0 " + what + " file://" +
         std::filesystem::absolute(page).string();
}

inline int run_command(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline std::string attribute(const std::string& dom, const std::string& name) {
  std::smatch m;
  const std::regex re("<body[^>]*\\s" + name + "=\"([^\"]*)\"");
  return std::regex_search(dom, m, re) ? m[1].str() : "";
}

/// Loads `page` and returns its DOM and console log (files in `work`).
inline Load load(const std::string& chromium, const std::string& page, const std::string& work,
                 int seconds = 90) {
  Load r;
  const std::string dom = work + "/dom.html", log = work + "/dom.log";
  r.code =
      run_command(chromium_command(chromium, work + "/profile-dom", "--dump-dom", page, seconds) +
                  " >" + dom + " 2>" + log + " </dev/null");
  r.dom = slurp(dom);
  r.log = slurp(log);
  r.rendered = attribute(r.dom, "data-rendered");
  const std::string errors = attribute(r.dom, "data-errors"), ms = attribute(r.dom, "data-load-ms");
  r.errors = errors.empty() ? -1 : std::atoi(errors.c_str());
  r.load_ms = ms.empty() ? -1.0 : std::atof(ms.c_str());
  std::stringstream lines(r.log);
  for (std::string line; std::getline(lines, line);)
    if (line.find("CONSOLE") != std::string::npos &&
        (line.find("Uncaught") != std::string::npos ||
         line.find("dresskit report:") != std::string::npos))
      r.console_errors.push_back(line);
  return r;
}

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  ///< width × height × 3
};

/// Reads a PNG (any colour type, 8-bit after libpng's transforms) as RGB.
inline Image read_png(const std::string& path) {
  Image image;
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) return image;
  png.format = PNG_FORMAT_RGB;
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
    png_image_free(&png);
    image.rgb.clear();
    return image;
  }
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  return image;
}

/// Takes a screenshot of `page` into `png` and returns the browser's exit code.
inline int screenshot(const std::string& chromium, const std::string& page, const std::string& png,
                      const std::string& work, int seconds = 90) {
  return run_command(
      chromium_command(chromium, work + "/profile-shot", "--screenshot=" + png, page, seconds) +
      " >" + work + "/shot.log 2>&1 </dev/null");
}

/// How a region of an image is coloured: its distinct colours, and the fraction of its pixels that
/// differ from the colour at its top-left corner (the background) by more than 12 in a channel.
struct Colours {
  int distinct = 0;
  double covered = 0.0;
};

inline Colours colours(const Image& image, int x0, int y0, int x1, int y1) {
  Colours c;
  if (image.rgb.empty()) return c;
  x1 = std::min(x1, image.width), y1 = std::min(y1, image.height);
  const unsigned char* bg = &image.rgb[3 * (static_cast<std::size_t>(y0) * image.width + x0)];
  std::set<int> seen;
  long covered = 0, all = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const unsigned char* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
      seen.insert((p[0] << 16) | (p[1] << 8) | p[2]);
      bool differs = false;
      for (int k = 0; k < 3; ++k) differs = differs || std::abs(p[k] - bg[k]) > 12;
      covered += differs;
      ++all;
    }
  c.distinct = static_cast<int>(seen.size());
  c.covered = all ? static_cast<double>(covered) / static_cast<double>(all) : 0.0;
  return c;
}

}  // namespace dresskit::test::browser
