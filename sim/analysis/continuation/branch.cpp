#include "sim/analysis/continuation/branch.h"

namespace metrosync::continuation {

const char* toString(BifurcationType t) {
  switch (t) {
    case BifurcationType::Fold:
      return "fold";
    case BifurcationType::Hopf:
      return "hopf";
    case BifurcationType::Branch:
      return "branch";
    case BifurcationType::Border:
      return "border";
  }
  return "?";
}

}  // namespace metrosync::continuation
