// What the X tools of the window tests share (xdnd_drop, x_key_tap):
// finding a top-level window by its title.
#pragma once

#include <X11/Xlib.h>

#include <string>

namespace bounce::test_support {

// Windows can vanish while the tree is walked (a BadWindow then): such
// errors are not the tools' to die of, so they are ignored and the walk
// goes on.
inline int ignore_x_errors(Display*, XErrorEvent*) {
  return 0;
}

// A window's title: _NET_WM_NAME (UTF-8, what GLFW and toolkits set) or
// else WM_NAME.
inline std::string window_name(Display* display, Window window) {
  const Atom net_wm_name = XInternAtom(display, "_NET_WM_NAME", False);
  const Atom utf8_string = XInternAtom(display, "UTF8_STRING", False);
  std::string name;
  Atom type = None;
  int format = 0;
  unsigned long count = 0, after = 0;
  unsigned char* data = nullptr;
  if (XGetWindowProperty(display, window, net_wm_name, 0, 1024, False, utf8_string, &type, &format, &count, &after,
                         &data) == Success &&
      data) {
    if (type == utf8_string && format == 8) name.assign(reinterpret_cast<char*>(data), count);
    XFree(data);
  }
  if (!name.empty()) return name;
  char* wm_name = nullptr;
  if (XFetchName(display, window, &wm_name) && wm_name) {
    name = wm_name;
    XFree(wm_name);
  }
  return name;
}

// The first window under `parent` (depth first) whose title contains
// `needle`. Without a window manager (Xvfb) that is a child of the root;
// with one, the named client window sits inside the manager's frame.
inline Window find_window(Display* display, Window parent, const std::string& needle) {
  Window root = 0, up = 0, *children = nullptr;
  unsigned int count = 0;
  if (!XQueryTree(display, parent, &root, &up, &children, &count)) return None;
  Window found = None;
  for (unsigned int i = 0; i < count && found == None; ++i) {
    if (window_name(display, children[i]).find(needle) != std::string::npos)
      found = children[i];
    else
      found = find_window(display, children[i], needle);
  }
  if (children) XFree(children);
  return found;
}

}  // namespace bounce::test_support
