"""``python -m impactcli`` runs the ``impact`` command line."""

from impactcli.cli import script

script()
