#pragma once
// Umbrella header of the train module.
#include "cnclab/train/lm.hpp"
#include "cnclab/train/mlp_residuals.hpp"
#include "cnclab/train/normal_equations.hpp"
#include "cnclab/train/objective.hpp"
#include "cnclab/train/residual_objective.hpp"
#include "cnclab/train/sgdm.hpp"
#include "cnclab/train/summary.hpp"
#include "cnclab/train/trainbr.hpp"
