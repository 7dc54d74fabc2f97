//! Expression and statement tests.
