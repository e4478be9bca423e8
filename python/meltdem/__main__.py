"""`python3 -m meltdem ...`: the `meltdem` command (tools/meltdem) run from the package."""
import sys

from . import paths
from .cli.main import main

paths.set_tool_environment()
sys.exit(main())
