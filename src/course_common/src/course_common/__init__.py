"""The workspace's shared code: what more than one package uses, owned by none of them."""
