import sys

from vcnc.cli import main

sys.exit(main())
