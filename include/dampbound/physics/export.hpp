#pragma once
// What libdampbound_core.so exports. Core compiles with hidden visibility (core/CMakeLists.txt);
// the public headers open their namespace with DAMPBOUND_API, so what they declare, and only
// that, is the shared library's interface. The static library is unaffected.
#if defined(__GNUC__) || defined(__clang__)
#define DAMPBOUND_API __attribute__((visibility("default")))
#else
#define DAMPBOUND_API
#endif
