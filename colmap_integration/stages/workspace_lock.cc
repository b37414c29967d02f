#include "colmap_integration/stages/workspace_lock.h"

namespace lutex {

std::filesystem::path WorkspaceLockPath(const Workspace& workspace) { return workspace.OutputDir() / ".lock"; }

std::unique_ptr<ExclusiveFileLock> LockWorkspaceFor(const Workspace& workspace, const InputsAndOutputs& paths) {
  if (!paths.WritesInside(workspace.OutputDir())) return nullptr;
  return std::make_unique<ExclusiveFileLock>(WorkspaceLockPath(workspace), workspace.root.string());
}

std::unique_ptr<ExclusiveFileLock> ClaimOutputs(const Workspace& workspace, const InputsAndOutputs& paths) {
  paths.Check();
  std::unique_ptr<ExclusiveFileLock> lock = LockWorkspaceFor(workspace, paths);
  paths.RemoveStaleTemporaries();
  return lock;
}

}  // namespace lutex
