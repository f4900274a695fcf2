#pragma once
// Everything of the engine (target aief::aief) in one include. The OpenCV adapter is a separate,
// optional target: include "aief/opencv.hpp" or "aief/orbslam2_extractor.hpp" for it.
#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "aief/features.hpp"
#include "aief/homography.hpp"
#include "aief/image.hpp"
#include "aief/match.hpp"
#include "aief/options.hpp"
#include "aief/version.hpp"
