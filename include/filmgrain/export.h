/* Symbol visibility of the installed library: the shared libfilmgrain is built with
 * hidden visibility, and only declarations marked FG_API (the C API, the C++ facade and
 * its error type) are exported. */
#ifndef FILMGRAIN_EXPORT_H
#define FILMGRAIN_EXPORT_H

#if defined(_WIN32)
#define FG_API
#elif defined(__GNUC__) || defined(__clang__)
#define FG_API __attribute__((visibility("default")))
#else
#define FG_API
#endif

#endif
