// x_key_tap: taps a key on a window, the press and the release sent back
// to back, as a quick finger does between two frames of a slow window.
// Tests use it under Xvfb, where no keyboard exists.
//
//   x_key_tap "<window title substring>" [ctrl+]<keysym name, e.g. Tab> [timeout seconds]
//
// Waits for the window (up to the timeout, default 60 s), then sends
// KeyPress and KeyRelease with one timestamp. Exit status: 0 once sent, 1
// on any failure (said on stderr), 2 for bad arguments.
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "x_windows.h"

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: x_key_tap \"<window title substring>\" [ctrl+]<keysym> [timeout seconds]\n");
    return 2;
  }
  const std::string needle = argv[1];
  std::string key_name = argv[2];
  unsigned int state = 0;
  if (key_name.starts_with("ctrl+")) {
    state = ControlMask;
    key_name = key_name.substr(5);
  }
  const KeySym keysym = XStringToKeysym(key_name.c_str());
  const double timeout = argc == 4 ? std::atof(argv[3]) : 60.0;
  if (keysym == NoSymbol || !(timeout > 0.0)) {
    std::fprintf(stderr, "x_key_tap: bad keysym '%s' or timeout\n", argv[2]);
    return 2;
  }
  Display* display = XOpenDisplay(nullptr);
  if (!display) {
    std::fprintf(stderr, "x_key_tap: cannot open the display\n");
    return 1;
  }
  XSetErrorHandler(bounce::test_support::ignore_x_errors);
  const Window root = DefaultRootWindow(display);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  Window target = None;
  while ((target = bounce::test_support::find_window(display, root, needle)) == None) {
    if (std::chrono::steady_clock::now() > deadline) {
      std::fprintf(stderr, "x_key_tap: no window titled '%s' within %g s\n", needle.c_str(), timeout);
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  XKeyEvent key{};
  key.display = display;
  key.window = target;
  key.root = root;
  key.subwindow = None;
  key.time = CurrentTime;
  key.same_screen = True;
  key.state = state;
  key.keycode = XKeysymToKeycode(display, keysym);
  for (const int type : {KeyPress, KeyRelease}) {
    key.type = type;
    XEvent event;
    event.xkey = key;
    XSendEvent(display, target, True, type == KeyPress ? KeyPressMask : KeyReleaseMask, &event);
  }
  XSync(display, False);
  XCloseDisplay(display);
  return 0;
}
