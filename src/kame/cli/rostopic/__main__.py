import sys

from kame.cli.rostopic import main

sys.exit(main())
