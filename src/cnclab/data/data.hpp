#pragma once
// Module data: datasets, dataset files, splits, generators.
#include "cnclab/data/dataset.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/data/friedman1.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/data/split.hpp"
