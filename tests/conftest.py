import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MECHANISMS = os.path.join(ROOT, "mechanisms")
sys.path.insert(0, ROOT)
