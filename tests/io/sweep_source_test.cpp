// placeholder: filled in by its owner in this session
