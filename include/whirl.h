/* whirl: steady shapes, dynamics and stability of a chain spun about the vertical axis. Includes
 * every public header of the library (tests/cli/install.sh checks it). */
#ifndef WHIRL_H
#define WHIRL_H

#include "whirl/common.h"
#include "whirl/version.h"
#include "whirl/chain.h"
#include "whirl/steady.h"
#include "whirl/dynamics.h"
#include "whirl/integrator.h"
#include "whirl/scene.h"
#include "whirl/stability.h"
#include "whirl/continuum_stability.h"
#include "whirl/atlas.h"
#include "whirl/optimize.h"
#include "whirl/driven.h"
#include "whirl/regime.h"
#include "whirl/periodic.h"

#endif
