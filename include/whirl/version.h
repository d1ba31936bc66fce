/* whirl: the library's version, MAJOR.MINOR.PATCH. The shared library's SONAME carries MAJOR
 * (libwhirl.so.MAJOR): it changes when a program built against an older version would break. */
#ifndef WHIRL_VERSION_H
#define WHIRL_VERSION_H

#include "whirl/common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WHIRL_VERSION_MAJOR 2
#define WHIRL_VERSION_MINOR 6
#define WHIRL_VERSION_PATCH 0

#define WHIRL_VERSION_STR_(x) #x
#define WHIRL_VERSION_XSTR_(x) WHIRL_VERSION_STR_(x)
/* "MAJOR.MINOR.PATCH" of the headers a program was compiled with */
#define WHIRL_VERSION                                                                          \
    WHIRL_VERSION_XSTR_(WHIRL_VERSION_MAJOR)                                                   \
    "." WHIRL_VERSION_XSTR_(WHIRL_VERSION_MINOR) "." WHIRL_VERSION_XSTR_(WHIRL_VERSION_PATCH)

/* The version of the library a program runs with, "MAJOR.MINOR.PATCH" (static storage); compare
 * it with WHIRL_VERSION to detect a library other than the one compiled against.
 * @return the version (static storage)
 */
WHIRL_API const char *whirl_version(void);

#ifdef __cplusplus
}
#endif

#endif
