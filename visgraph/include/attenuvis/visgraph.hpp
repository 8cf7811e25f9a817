// attenuvis::visgraph — Embree visibility graph weighted by contrast ratio
// C = exp(-sigma d) (Schwartz, Vinnikov, Federici, SimAUD 2021).
#pragma once

#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/footprints.hpp>
#include <attenuvis/visgraph/generators.hpp>
#include <attenuvis/visgraph/geojson.hpp>
#include <attenuvis/visgraph/ground.hpp>
#include <attenuvis/visgraph/limits.hpp>
#include <attenuvis/visgraph/mesh.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/obj.hpp>
#include <attenuvis/visgraph/outputs.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/scene_file.hpp>
#include <attenuvis/visgraph/space_syntax.hpp>
#include <attenuvis/visgraph/terrain.hpp>
#include <attenuvis/visgraph/visibility.hpp>
#include <attenuvis/visgraph/work_estimate.hpp>
