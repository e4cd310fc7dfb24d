//! Phase functions: one file each, dispatched by a closed enum.
