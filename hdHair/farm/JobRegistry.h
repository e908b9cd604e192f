#pragma once
// Which job folder a Slurm job id renders into, so that `hdhair-farm status
// 41` finds the folder: one small file per submitted job under
// $HDHAIR_FARM_REGISTRY, else $XDG_STATE_HOME/hdhair-farm/jobs, else
// ~/.local/state/hdhair-farm/jobs. (A job folder works as well as an id.)

#include <string>

namespace hdhair::farm {

void registerJob(const std::string& jobId, const std::string& jobFolder);

// The folder of `job`: a job folder given as such, or the registered folder
// of a job id. Throws std::runtime_error, one line, when it is neither.
std::string jobFolderOf(const std::string& job);

}  // namespace hdhair::farm
