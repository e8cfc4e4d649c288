angle increment: 45
function: /dev/zero
function: /dev/zero
function: /dev/zero
function: /dev/zero
function: /dev/zero
function: /dev/zero
function: /dev/zero
function: /dev/zero
function: /dev/zero
function: /dev/zero
