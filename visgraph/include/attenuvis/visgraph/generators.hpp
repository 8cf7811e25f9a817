// Every scene attenuvis ships as code, in one include: the classic layouts
// (layouts.hpp), the synthetic city (city.hpp) and the scene specs that name
// them on the command line (scene_spec.hpp).
#pragma once

#include <attenuvis/visgraph/city.hpp>
#include <attenuvis/visgraph/hillside.hpp>
#include <attenuvis/visgraph/layouts.hpp>
#include <attenuvis/visgraph/mesh.hpp>
#include <attenuvis/visgraph/scene_spec.hpp>
