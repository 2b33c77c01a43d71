// Parameter specs and factories of each method (one .cpp per method).
#pragma once

#include <memory>
#include <vector>

#include <rrlab/methods/method.hpp>

namespace rrlab {

#define RRLAB_DECLARE_METHOD(id)                  \
  std::vector<ParamSpec> id##_params();           \
  std::unique_ptr<Method> make_##id(const MethodContext& ctx);

RRLAB_DECLARE_METHOD(pinv)
RRLAB_DECLARE_METHOD(dls)
RRLAB_DECLARE_METHOD(gpm)
RRLAB_DECLARE_METHOD(task_priority)
RRLAB_DECLARE_METHOD(sr_task_priority)
RRLAB_DECLARE_METHOD(closest_point)
RRLAB_DECLARE_METHOD(posture_generation)
RRLAB_DECLARE_METHOD(ccp_voronoi)
RRLAB_DECLARE_METHOD(multi_preview)
RRLAB_DECLARE_METHOD(qp_constraints)
RRLAB_DECLARE_METHOD(direct_search)
RRLAB_DECLARE_METHOD(qp_ik)
RRLAB_DECLARE_METHOD(hqp)
RRLAB_DECLARE_METHOD(diffik)

#undef RRLAB_DECLARE_METHOD

}  // namespace rrlab
