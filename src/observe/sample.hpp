#pragma once
// Sample, Extremum and PopulationChange are what a stepper reports: defined in solve/.
#include "solve/observer.hpp"
