// The one Embree device of the program, and the conversion of Embree errors into GeometryError.
// Internal to src/query (the only folder that includes Embree).
#pragma once

#include <embree3/rtcore.h>

#include <memory>

namespace hm::query {

// Created on first use (thread-safe), with the default configuration: Embree's TBB tasking
// system then runs on the same oneTBB as hm::parallel_for, so tbb::global_control limits both.
// Lives until the program exits.
RTCDevice embree_device();

// An owned Embree scene, released when it goes out of scope.
struct SceneRelease {
  void operator()(RTCSceneTy* s) const { rtcReleaseScene(s); }
};
using ScenePtr = std::unique_ptr<RTCSceneTy, SceneRelease>;

// Throws GeometryError naming `what` when the device has an error pending on this thread (the
// message recorded by the error callback is appended). Clears the pending error.
void check_embree(const char* what);

}  // namespace hm::query
