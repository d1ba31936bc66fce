/* whirl: steady shapes, dynamics and stability of a chain spun about the vertical axis. */
#ifndef WHIRL_H
#define WHIRL_H

#include "whirl/common.h"
#include "whirl/chain.h"
#include "whirl/steady.h"
#include "whirl/dynamics.h"
#include "whirl/scene.h"
#include "whirl/stability.h"
#include "whirl/optimize.h"
#include "whirl/driven.h"

#endif
