"""One package per paper: its studies (datasets), claims (comparison rows) and figures. No paper imports another."""
