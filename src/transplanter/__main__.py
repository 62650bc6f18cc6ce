import sys

from transplanter.cli import main

sys.exit(main())
