// placeholder: replaced by the Simbody engine
