#pragma once
// Umbrella header of the train module.
#include "cnclab/train/objective.hpp"
#include "cnclab/train/sgdm.hpp"
#include "cnclab/train/summary.hpp"
