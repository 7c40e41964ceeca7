#pragma once
// Umbrella header of the nn module.
#include "cnclab/nn/activation.hpp"
#include "cnclab/nn/initializer.hpp"
#include "cnclab/nn/minmax.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/nn/narx.hpp"
#include "cnclab/nn/narx_predictor.hpp"
#include "cnclab/nn/zscore.hpp"
