"""`python -m kame.shell`: the same as `kame-setup` (prints the setup file's path)."""

import sys

from kame.shell import main

sys.exit(main())
