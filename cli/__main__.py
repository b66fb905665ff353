"""`python -m fastnms`: the command line."""

import sys

from fastnms.main import main

sys.exit(main())
