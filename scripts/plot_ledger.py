#!/usr/bin/python3
"""Plot a coupled run's ledger (postProcessing/particleLedger/ledger.csv): meltdem.cli.plot_ledger.

    plot_ledger.py ledger.csv [-o ledger.png] [-c mass enthalpy mom_y]
"""
import sys

from meltdem.cli.plot_ledger import main

if __name__ == "__main__":
    sys.exit(main())
