// placeholder: replaced by the rig loader
