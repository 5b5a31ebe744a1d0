# -*- Python -*-
import os
import subprocess

import lit.formats
from lit.llvm import llvm_config
from lit.llvm.subst import ToolSubst

config.name = "Simit"
config.test_format = lit.formats.ShTest(not llvm_config.use_lit_shell)
config.suffixes = [".mlir", ".sim", ".test"]
config.excludes = ["Inputs", "lit.cfg.py", "CMakeLists.txt"]
config.test_source_root = os.path.dirname(__file__)
config.test_exec_root = os.path.join(config.simit_obj_root, "test")

config.substitutions.append(("%PATH%", config.environment["PATH"]))
config.substitutions.append(("%simit_src", config.simit_src_root))
config.substitutions.append(("%simit_obj", config.simit_obj_root))
config.substitutions.append(("%shared", config.shared_dir))
if config.simit_build_python:
    config.available_features.add("simit-python")
config.substitutions.append(("%python3", config.python3_executable))
# Builds shared libraries of host functions (extern func) for the tests.
config.substitutions.append(("%host_cxx", config.host_cxx))
config.substitutions.append(("%simit_python_dir", config.simit_python_install_dir))
config.substitutions.append(("%meshes", os.path.join(config.shared_dir, "data", "meshes")))

# SIMIT_NUM_THREADS reaches simit-run, so that scripts/test can run the
# suite on a given number of threads.
llvm_config.with_system_environment(["HOME", "INCLUDE", "LIB", "TMP", "TEMP",
                                     "SIMIT_NUM_THREADS"])
# simit-run's compile cache defaults to $XDG_CACHE_HOME/simit: the suite's
# entries stay in the build tree, out of the user's cache.
config.environment["XDG_CACHE_HOME"] = os.path.join(config.test_exec_root,
                                                    "xdg-cache")
llvm_config.use_default_substitutions()

# Feature cuda-device: simit-run finds a CUDA device (docs/gpu.md). The
# answer is printed once, so a run without one says so in one line; tests
# that need a device are then reported UNSUPPORTED, not passed.
simit_run = os.path.join(config.simit_tools_dir, "simit-run")
try:
    probe = subprocess.run([simit_run, "--cuda-device"], capture_output=True,
                           text=True, timeout=300)
    answer = (probe.stdout + probe.stderr).strip()
    if probe.returncode == 0:
        config.available_features.add("cuda-device")
except (OSError, subprocess.TimeoutExpired) as error:
    answer = f"no CUDA device: cannot run {simit_run}: {error}"
lit_config.note(answer.replace("simit-run: ", ""))

# --param simit_target=gpu runs every simit-run of the suite with
# --target gpu (scripts/gpu-check); tests of the CPU target's own output
# say UNSUPPORTED: target-gpu.
simit_target = lit_config.params.get("simit_target", "cpu")
if simit_target not in ("cpu", "gpu"):
    lit_config.fatal(f"simit_target must be cpu or gpu, not {simit_target}")
config.available_features.add("target-" + simit_target)

tool_dirs = [config.simit_tools_dir, config.llvm_tools_dir]
tools = ["simit-opt", "simit-translate", "simit-bench-eigen",
         "simit-bench-sherman-morrison", "simit-bench-spmv", "mlir-opt",
         "mlir-runner",
         ToolSubst("simit-run", extra_args=["--target", simit_target]
                   if simit_target == "gpu" else None)]
llvm_config.add_tool_substitutions(tools, tool_dirs)
llvm_config.with_environment("PATH", config.llvm_tools_dir, append_path=True)
llvm_config.with_environment("PATH", config.simit_tools_dir, append_path=True)
