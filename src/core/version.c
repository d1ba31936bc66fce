/* whirl_version: the version the library was built as. */
#include "whirl/version.h"

const char *whirl_version(void) { return WHIRL_VERSION; }
