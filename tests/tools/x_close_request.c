/* x_close_request PID: asks the top-level window of process PID to close as a window manager's
 * close button does (a WM_PROTOCOLS / WM_DELETE_WINDOW client message), then prints the
 * monotonic time of the request in nanoseconds. Xvfb runs no window manager and xdotool 3.2016
 * has no such command (its windowclose destroys the window, windowkill ends the client), so
 * tests/cli/gui_close.sh uses this. Exit 1 when no window of PID is mapped within 10 s. */
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

static long window_pid(Display* d, Window w, Atom net_wm_pid) {
  Atom type;
  int format;
  unsigned long n, after;
  unsigned char* data = NULL;
  long pid = -1;
  if (XGetWindowProperty(d, w, net_wm_pid, 0, 1, False, XA_CARDINAL, &type, &format, &n, &after,
                         &data) == Success && data != NULL) {
    if (n == 1) pid = (long)*(unsigned long*)data;
    XFree(data);
  }
  return pid;
}

static Window find(Display* d, Window w, long pid, Atom net_wm_pid) {
  if (window_pid(d, w, net_wm_pid) == pid) {
    XWindowAttributes a;
    if (XGetWindowAttributes(d, w, &a) && a.map_state == IsViewable) return w;
  }
  Window root, parent, *kids = NULL;
  unsigned int n = 0;
  Window found = 0;
  if (XQueryTree(d, w, &root, &parent, &kids, &n)) {
    for (unsigned int i = 0; i < n && !found; ++i) found = find(d, kids[i], pid, net_wm_pid);
    if (kids) XFree(kids);
  }
  return found;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: x_close_request PID\n");
    return 2;
  }
  const long pid = atol(argv[1]);
  Display* d = XOpenDisplay(NULL);
  if (!d) {
    fprintf(stderr, "x_close_request: cannot open the display\n");
    return 2;
  }
  const Atom net_wm_pid = XInternAtom(d, "_NET_WM_PID", False);
  Window w = 0;
  for (int tries = 0; tries < 1000 && !w; ++tries) {
    w = find(d, DefaultRootWindow(d), pid, net_wm_pid);
    if (!w) usleep(10000);
  }
  if (!w) {
    fprintf(stderr, "x_close_request: no mapped window of process %ld\n", pid);
    return 1;
  }
  XEvent e = {0};
  e.xclient.type = ClientMessage;
  e.xclient.window = w;
  e.xclient.message_type = XInternAtom(d, "WM_PROTOCOLS", False);
  e.xclient.format = 32;
  e.xclient.data.l[0] = (long)XInternAtom(d, "WM_DELETE_WINDOW", False);
  e.xclient.data.l[1] = CurrentTime;
  struct timespec t;
  clock_gettime(CLOCK_REALTIME, &t);
  XSendEvent(d, w, False, NoEventMask, &e);
  XSync(d, False);
  printf("%lld\n", (long long)t.tv_sec * 1000000000LL + t.tv_nsec);
  XCloseDisplay(d);
  return 0;
}
