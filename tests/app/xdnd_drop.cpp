// xdnd_drop: drops a file on a window the way a file manager does, over
// the XDND protocol (version 5, freedesktop.org "Drag-and-Drop Protocol for
// the X Window System"). Tests use it under Xvfb, where no real drag can be
// made and no X tool performs one.
//
//   xdnd_drop "<window title substring>" <absolute file path> [timeout seconds]
//
// Exit status: 0 once the target reports the drop finished, 1 on any
// failure (said on stderr), 2 for bad arguments.
//
// The conversation, seen from the source (this program):
//   1. own the XdndSelection selection (the target fetches the data from it);
//   2. XdndEnter: our protocol version and the data types on offer;
//   3. XdndPosition: where the pointer is and the action wanted;
//   4. wait for XdndStatus: does the target accept a drop there?
//   5. XdndDrop; the target asks for the data with XConvertSelection, which
//      reaches us as a SelectionRequest: we write the text/uri-list into
//      the property it names and tell it with SelectionNotify;
//   6. wait for XdndFinished.
#include <X11/Xatom.h>
#include <X11/Xlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "x_windows.h"

namespace {

using clock_type = std::chrono::steady_clock;

constexpr long xdnd_version = 5;  // the newest XDND version, as GLFW 3.3 speaks it

struct atoms {
  Atom aware, selection, enter, position, status, drop, finished, leave, action_copy, uri_list, timestamp_probe;
};

atoms intern_atoms(Display* display) {
  auto atom = [display](const char* name) { return XInternAtom(display, name, False); };
  return {atom("XdndAware"),      atom("XdndSelection"), atom("XdndEnter"),     atom("XdndPosition"),
          atom("XdndStatus"),     atom("XdndDrop"),      atom("XdndFinished"),  atom("XdndLeave"),
          atom("XdndActionCopy"), atom("text/uri-list"), atom("XDND_DROP_TIME")};
}

// The XDND version the target supports (its XdndAware property), or -1
// when it has none: then it accepts no drops.
long aware_version(Display* display, Window window, const atoms& a) {
  Atom type = None;
  int format = 0;
  unsigned long count = 0, after = 0;
  unsigned char* data = nullptr;
  long version = -1;
  if (XGetWindowProperty(display, window, a.aware, 0, 1, False, XA_ATOM, &type, &format, &count, &after, &data) ==
          Success &&
      data) {
    if (type == XA_ATOM && format == 32 && count == 1) version = static_cast<long>(*reinterpret_cast<Atom*>(data));
    XFree(data);
  }
  return version;
}

// A server timestamp: the spec wants real times on the selection and the
// drop (CurrentTime is ambiguous). An empty append to a property of our own
// window makes the server send a PropertyNotify carrying its time.
Time server_time(Display* display, Window window, const atoms& a) {
  XSelectInput(display, window, PropertyChangeMask);
  XChangeProperty(display, window, a.timestamp_probe, XA_STRING, 8, PropModeAppend, nullptr, 0);
  XEvent event;
  XWindowEvent(display, window, PropertyChangeMask, &event);
  return event.xproperty.time;
}

// file:// URI of an absolute path, with the bytes a URI may not hold
// percent-encoded (GLFW and the toolkits decode them).
std::string file_uri(const std::string& path) {
  static const char hex[] = "0123456789ABCDEF";
  std::string uri = "file://";
  for (unsigned char c : path) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '/' ||
                       c == '-' || c == '_' || c == '.' || c == '~';
    if (plain) {
      uri += static_cast<char>(c);
    } else {
      uri += '%';
      uri += hex[c >> 4];
      uri += hex[c & 15];
    }
  }
  return uri;
}

// Sends an XDND client message to the target; data.l[0] is always the
// source window.
void send_message(Display* display, Window target, Window source, Atom type, long l1, long l2, long l3, long l4) {
  XEvent event{};
  event.xclient.type = ClientMessage;
  event.xclient.window = target;
  event.xclient.message_type = type;
  event.xclient.format = 32;
  event.xclient.data.l[0] = static_cast<long>(source);
  event.xclient.data.l[1] = l1;
  event.xclient.data.l[2] = l2;
  event.xclient.data.l[3] = l3;
  event.xclient.data.l[4] = l4;
  // No event mask: delivered to the client that created the target window.
  XSendEvent(display, target, False, NoEventMask, &event);
  XFlush(display);
}

struct source_state {
  Window window = None;
  std::string uri_list;  // the data on offer
  bool data_sent = false;
};

// The target's request for the dragged data (after XdndDrop it calls
// XConvertSelection(XdndSelection, text/uri-list, <property>, <its window>)).
// Anything else is refused with property None, as ICCCM says.
void answer_selection_request(Display* display, const XSelectionRequestEvent& request, const atoms& a,
                              source_state& source) {
  XEvent reply{};
  reply.xselection.type = SelectionNotify;
  reply.xselection.requestor = request.requestor;
  reply.xselection.selection = request.selection;
  reply.xselection.target = request.target;
  reply.xselection.time = request.time;
  reply.xselection.property = None;
  if (request.selection == a.selection && request.target == a.uri_list) {
    // Obsolete requestors name no property: then the target atom is used.
    const Atom property = request.property != None ? request.property : request.target;
    XChangeProperty(display, request.requestor, property, a.uri_list, 8, PropModeReplace,
                    reinterpret_cast<const unsigned char*>(source.uri_list.data()),
                    static_cast<int>(source.uri_list.size()));
    reply.xselection.property = property;
    source.data_sent = true;
  }
  XSendEvent(display, request.requestor, False, NoEventMask, &reply);
  XFlush(display);
}

// Waits until the deadline for a client message of `type` to our source
// window, answering selection requests meanwhile. False on timeout.
bool wait_for_message(Display* display, Atom type, clock_type::time_point deadline, const atoms& a,
                      source_state& source, XClientMessageEvent& out) {
  while (clock_type::now() < deadline) {
    while (XPending(display)) {
      XEvent event;
      XNextEvent(display, &event);
      if (event.type == SelectionRequest) {
        answer_selection_request(display, event.xselectionrequest, a, source);
      } else if (event.type == ClientMessage && event.xclient.message_type == type &&
                 event.xclient.window == source.window) {
        out = event.xclient;
        return true;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

int fail(const std::string& message) {
  std::fprintf(stderr, "xdnd_drop: %s\n", message.c_str());
  return 1;
}

std::string hex_id(Window window) {
  char text[32];
  std::snprintf(text, sizeof text, "0x%lx", static_cast<unsigned long>(window));
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: xdnd_drop \"<window title substring>\" <absolute file path> [timeout seconds]\n");
    return 2;
  }
  const std::string needle = argv[1], path = argv[2];
  double timeout = 30.0;
  std::string argv_timeout = "30";
  if (argc == 4) {
    char* end = nullptr;
    timeout = std::strtod(argv[3], &end);
    argv_timeout = argv[3];
    if (end == argv[3] || *end != '\0' || !(timeout > 0.0)) {
      std::fprintf(stderr, "xdnd_drop: the timeout '%s' is not a positive number of seconds\n", argv[3]);
      return 2;
    }
  }
  if (path.empty() || path[0] != '/') {
    std::fprintf(stderr, "xdnd_drop: '%s' is not an absolute path (a file URI needs one)\n", path.c_str());
    return 2;
  }
  const auto deadline =
      clock_type::now() + std::chrono::duration_cast<clock_type::duration>(std::chrono::duration<double>(timeout));

  const char* display_name = std::getenv("DISPLAY");
  Display* display = XOpenDisplay(nullptr);
  if (!display)
    return fail(std::string("cannot open the X display '") + (display_name ? display_name : "") +
                "' (is DISPLAY set? run under xvfb-run)");
  XSetErrorHandler(bounce::test_support::ignore_x_errors);
  const atoms a = intern_atoms(display);
  const Window root = DefaultRootWindow(display);

  // The target: the window that program is opening may not exist yet, so
  // look again until the deadline.
  Window target = None;
  while ((target = bounce::test_support::find_window(display, root, needle)) == None) {
    if (clock_type::now() >= deadline)
      return fail("no window with '" + needle + "' in its title appeared within " + argv_timeout + " s");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }

  // Only windows that say they speak XDND (XdndAware, set on the top-level
  // window; GLFW sets version 5) may be sent its messages; we speak the
  // lower of our two versions.
  const long aware = aware_version(display, target, a);
  if (aware < 0)
    return fail("window " + hex_id(target) + " ('" + bounce::test_support::window_name(display, target) +
                "') has no XdndAware property: it accepts no drops");
  const long version = std::min(aware, xdnd_version);
  if (version < 2) return fail("window " + hex_id(target) + " speaks XDND " + std::to_string(aware) + ", below 2");

  // Where the pointer "is": the target's centre, in root coordinates (what
  // XdndPosition carries).
  XWindowAttributes attributes;
  if (!XGetWindowAttributes(display, target, &attributes)) return fail("window " + hex_id(target) + " went away");
  int x = 0, y = 0;
  Window child = None;
  XTranslateCoordinates(display, target, root, attributes.width / 2, attributes.height / 2, &x, &y, &child);

  // 1. The source window: unmapped, it only names us in the messages and
  // owns the selection the target reads the data from.
  source_state source;
  source.window = XCreateSimpleWindow(display, root, 0, 0, 1, 1, 0, 0, 0);
  source.uri_list = file_uri(path) + "\r\n";
  const Time time = server_time(display, source.window, a);
  XSetSelectionOwner(display, a.selection, source.window, time);
  if (XGetSelectionOwner(display, a.selection) != source.window) return fail("cannot own the XdndSelection selection");

  // 2. XdndEnter: data.l[1] holds the version in its top byte; bit 0 clear
  // says the types are all in l[2..4] (no XdndTypeList property needed).
  send_message(display, target, source.window, a.enter, version << 24, static_cast<long>(a.uri_list), None, None);

  // 3. XdndPosition: l[2] = x << 16 | y on the root window, l[3] the time,
  // l[4] the action asked for.
  send_message(display, target, source.window, a.position, 0, (static_cast<long>(x) << 16) | (y & 0xffff),
               static_cast<long>(time), static_cast<long>(a.action_copy));

  // 4. XdndStatus: bit 0 of l[1] says the target would accept a drop here.
  XClientMessageEvent status{};
  if (!wait_for_message(display, a.status, deadline, a, source, status))
    return fail("window " + hex_id(target) + " sent no XdndStatus after XdndPosition (is its event loop running?)");
  if (!(status.data.l[1] & 1)) {
    send_message(display, target, source.window, a.leave, 0, 0, 0, 0);  // end the drag politely
    return fail("window " + hex_id(target) + " does not accept a text/uri-list drop (XdndStatus refused it)");
  }

  // 5. XdndDrop: l[2] is the time the target uses to ask for the selection.
  send_message(display, target, source.window, a.drop, 0, static_cast<long>(time), 0, 0);

  // 6. XdndFinished: the target has taken the data. Its l[1] says whether
  // the drop succeeded (bit 0 in the spec; GLFW 3.3 puts the byte count of
  // the data there, so any non-zero value counts).
  XClientMessageEvent finished{};
  if (!wait_for_message(display, a.finished, deadline, a, source, finished))
    return fail(source.data_sent ? "the target took the data but sent no XdndFinished"
                                 : "window " + hex_id(target) + " never asked for the dropped data nor finished");
  if (finished.data.l[1] == 0) return fail("window " + hex_id(target) + " reports that the drop failed");
  if (!source.data_sent) return fail("window " + hex_id(target) + " finished without asking for the data");

  XDestroyWindow(display, source.window);
  XCloseDisplay(display);
  std::printf("xdnd_drop: dropped %s on window %s\n", path.c_str(), hex_id(target).c_str());
  return 0;
}
