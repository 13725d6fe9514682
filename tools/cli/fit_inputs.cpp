#include "tools/cli/fit_inputs.h"

#include "tools/cli/commands.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

Rig loadPhysicalRig(const std::string& text, const std::string& name,
                    const std::vector<std::string>& sets) {
  Rig rig = loadRigText(text, name, sets);
  if (rig.units != Units::Physical)
    throw UsageError(name +
                     ": a scaled rig (units: scaled) has no seconds or radians to match "
                     "measured data; write the rig in physical units");
  return rig;
}

MeasuredData loadData(const std::string& path, const Rig& rig) {
  try {
    return readDataFile(path, static_cast<int>(rig.metronomes.size()));
  } catch (const DataError& e) {
    throw UsageError(e.what());
  }
}

}  // namespace metrosync::cli
