#include "cli/entity_names.h"

namespace hm::cli {

const char* iges_entity_name(int type) {
  switch (type) {
    case 100:
      return "circular arc";
    case 102:
      return "composite curve";
    case 104:
      return "conic arc";
    case 106:
      return "copious data";
    case 108:
      return "plane";
    case 110:
      return "line";
    case 112:
      return "parametric spline curve";
    case 114:
      return "parametric spline surface";
    case 116:
      return "point";
    case 118:
      return "ruled surface";
    case 120:
      return "surface of revolution";
    case 122:
      return "tabulated cylinder";
    case 123:
      return "direction";
    case 124:
      return "transformation matrix";
    case 126:
      return "rational B-spline curve";
    case 128:
      return "rational B-spline surface";
    case 141:
      return "boundary";
    case 142:
      return "curve on a parametric surface";
    case 143:
      return "bounded surface";
    case 144:
      return "trimmed surface";
    case 186:
      return "manifold solid B-rep";
    case 190:
      return "plane surface";
    case 212:
      return "general note";
    case 314:
      return "colour definition";
    case 402:
      return "associativity (group)";
    case 406:
      return "property";
    case 410:
      return "view";
    case 502:
      return "vertex list";
    case 504:
      return "edge list";
    case 508:
      return "loop";
    case 510:
      return "face";
    case 514:
      return "shell";
    default:
      return "entity";
  }
}

}  // namespace hm::cli
