"""The process around the cores: how a process of ours starts, supervises and ends others, and its own
settings (docs/architecture.md). Plain Python, no rclpy:

- :mod:`.memory`: glibc's malloc thresholds raised for an analysing process (no page fault per reused array);
- :mod:`.supervisor`: starts the graph's processes and ends them all, children included;
- :mod:`.parent_watch`: a child process that ends itself when its parent is gone;
- :mod:`.subscriber_wait`: how long a publisher waits for its subscribers before it starts.
"""
