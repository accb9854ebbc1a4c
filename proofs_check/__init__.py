"""proofs_check: the independent exact checker of trackcert certificates.

Standard library only (``fractions``, ``json``); it imports nothing from ``theory``. Usage::

    python -m proofs_check FILE [--json]

Exit codes: 0 every check holds, 1 some check fails, 2 the file is malformed or refused.
The format and each kind's claim are documented in ``docs/certificates.md``.
"""

from proofs_check.parse import FORMAT, MalformedError
from proofs_check.verify import Verdict, check_certificate, check_file

__all__ = ["FORMAT", "MalformedError", "Verdict", "check_certificate", "check_file"]
