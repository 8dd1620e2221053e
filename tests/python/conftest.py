# SPDX-License-Identifier: BSD-3-Clause
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """The contourmesh command of this build (ctest sets CONTOURMESH_CLI)."""
    path = os.environ.get("CONTOURMESH_CLI")
    if not path:
        pytest.skip("CONTOURMESH_CLI is not set (run through ctest)")
    return lambda *args: subprocess.run([path, *map(str, args)], check=True, capture_output=True, text=True)
