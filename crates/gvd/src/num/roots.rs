//! Certified real root isolation. STUB: the numerics helper replaces this file.
