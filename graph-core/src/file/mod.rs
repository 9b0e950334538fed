//! RON graph files: schema, plugin registry, loader with file:line:col errors.
