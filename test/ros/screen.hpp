// Helpers of the end-to-end rostest: an Xvfb display and a program on it (child processes that
// die with the test), screenshots (imagemagick `import`) and counting pixels of one hue.
#pragma once

#include <fcntl.h>
#include <memory>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace ragdoll_test {

// A child process (argv[0] looked up on PATH) with extra environment `env` ("K=V"), its
// output appended to `log`; SIGTERM on destruction, and the kernel sends it SIGTERM if the test
// dies first.
class Child {
 public:
  Child(const std::vector<std::string>& argv, const std::vector<std::string>& env,
        const std::string& log = "/dev/null") {
    pid_ = fork();
    if (pid_ != 0) return;
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    for (const std::string& e : env) putenv(const_cast<char*>(e.c_str()));
    const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (out >= 0) {
      dup2(out, 1);
      dup2(out, 2);
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    _exit(127);
  }
  ~Child() { stop(); }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  bool running() {
    if (pid_ <= 0) return false;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return false;
    }
    return true;
  }

  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    for (int i = 0; i < 50; ++i) {  // up to 5 s, then SIGKILL
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return;
      }
      usleep(100000);
    }
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
};

// Xvfb on the first free display: it writes the display number to a pipe (-displayfd).
class Xvfb {
 public:
  explicit Xvfb(const std::string& log, const std::string& screen = "1280x1024x24") {
    int fds[2];
    if (pipe(fds) != 0) return;
    child_ = std::make_unique<Child>(
        std::vector<std::string>{"Xvfb", "-displayfd", std::to_string(fds[1]), "-screen", "0",
                                 screen, "-nolisten", "tcp"},
        std::vector<std::string>{}, log);
    close(fds[1]);
    std::string number;
    char c;
    while (read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    close(fds[0]);
    if (!number.empty()) display_ = ":" + number;
  }
  const std::string& display() const { return display_; }  // "" if it did not start
  Child* child() { return child_.get(); }

 private:
  std::unique_ptr<Child> child_;
  std::string display_;
};

// An RGB image (8 bits per channel).
struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  bool valid() const { return width > 0 && height > 0; }
};

// Screenshot of the whole display to `png`, read back as RGB. Invalid on failure.
inline Image screenshot(const std::string& display, const std::string& png) {
  Image img;
  const std::string cmd = "import -display " + display + " -window root '" + png + "' 2>/dev/null";
  if (std::system(cmd.c_str()) != 0) return img;
  FILE* f = popen(("convert '" + png + "' -depth 8 ppm:- 2>/dev/null").c_str(), "r");
  if (!f) return img;
  int w = 0, h = 0, maxval = 0;
  if (fscanf(f, "P6 %d %d %d", &w, &h, &maxval) == 3 && maxval == 255 && fgetc(f) != EOF) {
    img.rgb.resize(static_cast<size_t>(w) * h * 3);
    if (fread(img.rgb.data(), 1, img.rgb.size(), f) == img.rgb.size()) {
      img.width = w;
      img.height = h;
    }
  }
  pclose(f);
  return img;
}

inline double hueDeg(double r, double g, double b) {
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b}), c = mx - mn;
  if (c <= 0.0) return 0.0;
  double h;
  if (mx == r) h = std::fmod((g - b) / c, 6.0);
  else if (mx == g) h = (b - r) / c + 2.0;
  else h = (r - g) / c + 4.0;
  h *= 60.0;
  return h < 0.0 ? h + 360.0 : h;
}

// Pixels of the hue of colour (r, g, b) (0..1): within `tolerance` degrees of its hue,
// saturated (shading keeps the hue; the grey background, grid and ground are unsaturated) and
// not too dark. A mask, one entry per pixel.
inline std::vector<bool> hueMask(const Image& img, double r, double g, double b,
                                 double tolerance = 12.0) {
  const double h0 = hueDeg(r, g, b);
  std::vector<bool> mask(static_cast<size_t>(img.width) * img.height, false);
  for (size_t i = 0; i < mask.size(); ++i) {
    const double R = img.rgb[3 * i] / 255.0, G = img.rgb[3 * i + 1] / 255.0, B = img.rgb[3 * i + 2] / 255.0;
    const double mx = std::max({R, G, B}), mn = std::min({R, G, B});
    if (mx < 0.15 || (mx - mn) / mx < 0.35) continue;
    double d = std::abs(hueDeg(R, G, B) - h0);
    d = std::min(d, 360.0 - d);
    mask[i] = d <= tolerance;
  }
  return mask;
}

inline double fraction(const std::vector<bool>& mask) {
  if (mask.empty()) return 0.0;
  return static_cast<double>(std::count(mask.begin(), mask.end(), true)) / mask.size();
}

// Share of the pixels in either mask that are in only one of them (0: the same, 1: disjoint).
inline double changed(const std::vector<bool>& a, const std::vector<bool>& b) {
  size_t either = 0, one = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    either += a[i] || b[i];
    one += a[i] != b[i];
  }
  return either ? static_cast<double>(one) / either : 0.0;
}

}  // namespace ragdoll_test
