initial line width: 99999999999 pixels
