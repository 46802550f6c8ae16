// The process's one Embree device (it owns a thread pool), shared by the
// files that build Embree scenes. Internal to core/.
#pragma once

#include <embree3/rtcore.h>

namespace bounce {

RTCDevice embree_device();

}  // namespace bounce
